# Test of cmake/segmentation_methods_from_idl.cmake (ctest core_segmentation_methods_from_idl):
# the name conversion, comments, rewriting only on change, and every refusal with its message.
#   cmake -DSCRIPT=cmake/segmentation_methods_from_idl.cmake -DWORK_DIR=<scratch folder> -P this file
cmake_minimum_required(VERSION 3.22)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# check(<if() condition as text> <what>): a failed check fails the test and the run goes on.
function(check condition what)
  cmake_language(EVAL CODE "if(${condition})\n set(ok TRUE)\nelse()\n set(ok FALSE)\nendif()")
  if(NOT ok)
    message(SEND_ERROR "FAILED: ${what}")
  endif()
endfunction()

# generate(<case> <idl text>): writes <case>.idl, runs the script into <case>.inc; sets rc, out, err.
function(generate case idl)
  file(WRITE "${WORK_DIR}/${case}.idl" "${idl}")
  execute_process(COMMAND "${CMAKE_COMMAND}" -DIDL=${WORK_DIR}/${case}.idl -DOUTPUT=${WORK_DIR}/${case}.inc -P "${SCRIPT}"
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  set(out "")
  if(EXISTS "${WORK_DIR}/${case}.inc")
    file(READ "${WORK_DIR}/${case}.inc" out)
  endif()
  string(REGEX REPLACE "[ \t\r\n]+" " " err "${err}")  # CMake wraps long messages
  set(rc "${rc}" PARENT_SCOPE)
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

# Names: lower case; enumerators: each word capitalised; order kept; comments are no methods.
generate(good [[
module uavmot { module msg {
enum Other { NOT_A_METHOD };
enum SegmentationMethod {
    CLUSTERING,   // the paper's five
    KORN,
    // RETIRED,
    MORPHOLOGICAL, /* LBP_OLD, */
    LBP,
    FUSION,
    SOBEL_3X3,
    A_B_C
};
}; };
]])
check("rc EQUAL 0" "a good enum is read (${err})")
string(FIND "${out}" [[#define UAVMOT_SEGMENTATION_METHODS(X) \
  X(Clustering, "clustering") \
  X(Korn, "korn") \
  X(Morphological, "morphological") \
  X(Lbp, "lbp") \
  X(Fusion, "fusion") \
  X(Sobel3x3, "sobel_3x3") \
  X(ABC, "a_b_c")
]] at)
check("NOT at EQUAL -1" "the list, converted and in order:\n${out}")
foreach(absent RETIRED LBP_OLD NOT_A_METHOD Retired LbpOld NotAMethod)
  string(FIND "${out}" "${absent}" at)
  check("at EQUAL -1" "${absent} is not listed:\n${out}")
endforeach()

# The same enum again rewrites nothing (so nothing recompiles); a changed enum rewrites the list.
file(TIMESTAMP "${WORK_DIR}/good.inc" before "%s")
execute_process(COMMAND "${CMAKE_COMMAND}" -E sleep 1.1)
file(READ "${WORK_DIR}/good.idl" idl)
file(WRITE "${WORK_DIR}/good.idl" "// an edit outside the enum\n${idl}")
execute_process(COMMAND "${CMAKE_COMMAND}" -DIDL=${WORK_DIR}/good.idl -DOUTPUT=${WORK_DIR}/good.inc -P "${SCRIPT}"
                RESULT_VARIABLE rc)
file(TIMESTAMP "${WORK_DIR}/good.inc" after "%s")
check("rc EQUAL 0" "regenerating")
check("before EQUAL after" "an unchanged list is not rewritten (${before} -> ${after})")
string(REPLACE "A_B_C" "A_B_C,\n    D" idl "${idl}")
generate(good "${idl}")
string(FIND "${out}" [[  X(ABC, "a_b_c") \
  X(D, "d")
]] at)
check("NOT at EQUAL -1" "an appended method is listed:\n${out}")

# Refusals: the build stops with the IDL's name and the reason, and writes no list.
# (No ';' in these IDL texts: they travel in a CMake list.)
foreach(case_reason
    "missing|enum Segmentation { A, B }|no such enum"
    "twice|enum SegmentationMethod { A } enum SegmentationMethod { B }|defined 2 times"
    "empty|enum SegmentationMethod { /* none */ }|lists no enumerator"
    "value|enum SegmentationMethod { A = 1, B }|'A = 1' is not an UPPER_SNAKE_CASE enumerator"
    "lower|enum SegmentationMethod { Korn }|'Korn' is not an UPPER_SNAKE_CASE enumerator"
    "gap|enum SegmentationMethod { A, , B }|'' is not an UPPER_SNAKE_CASE enumerator"
    "repeated|enum SegmentationMethod { A, B, A }|'A' is listed twice")
  string(REPLACE "|" ";" parts "${case_reason}")
  list(GET parts 0 case)
  list(GET parts 1 idl)
  list(GET parts 2 reason)
  generate(${case} "${idl}")
  check("NOT rc EQUAL 0" "${case}: refused")
  string(FIND "${err}" "${case}.idl: cannot read the segmentation methods" at)
  check("NOT at EQUAL -1" "${case}: the message names the file: ${err}")
  string(FIND "${err}" "${reason}" at)
  check("NOT at EQUAL -1" "${case}: the message says '${reason}': ${err}")
  check("NOT EXISTS ${WORK_DIR}/${case}.inc" "${case}: no list written")
endforeach()
execute_process(COMMAND "${CMAKE_COMMAND}" -DIDL=${WORK_DIR}/absent.idl -DOUTPUT=${WORK_DIR}/absent.inc -P "${SCRIPT}"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
check("NOT rc EQUAL 0" "a missing IDL file is refused")
