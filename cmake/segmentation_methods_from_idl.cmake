# Writes the list of segmentation methods, UAVMOT_SEGMENTATION_METHODS(X), from the
# `enum SegmentationMethod` of idl/segmentation.idl: the IDL is the one list (the wire contract),
# and core reads only its text, never Fast DDS.
#
#   cmake -DIDL=idl/segmentation.idl -DOUTPUT=.../segmentation_methods.inc -P segmentation_methods_from_idl.cmake
#
# Each enumerator, in the IDL's order (its number on the wire), becomes X(Enumerator, "name"):
# KORN -> X(Korn, "korn"), SOME_METHOD -> X(SomeMethod, "some_method"). The output is rewritten
# only when its text changes, so an edit elsewhere in the IDL recompiles nothing of core.
# Anything it cannot read (no such enum, an empty one, an enumerator that is not UPPER_SNAKE_CASE,
# an explicit value, a repeated name) stops the build with a message naming the IDL file.
cmake_minimum_required(VERSION 3.22)

function(uavmot_segmentation_methods_fail idl why)
  message(FATAL_ERROR "${idl}: cannot read the segmentation methods from `enum SegmentationMethod { ... }`: ${why}")
endfunction()

if(NOT DEFINED IDL OR NOT DEFINED OUTPUT)
  message(FATAL_ERROR "usage: cmake -DIDL=segmentation.idl -DOUTPUT=segmentation_methods.inc -P ${CMAKE_CURRENT_LIST_FILE}")
endif()
if(NOT EXISTS "${IDL}")
  uavmot_segmentation_methods_fail("${IDL}" "no such file")
endif()

file(READ "${IDL}" text)
# Comments out first: a commented-out enumerator is no method.
string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" " " text "${text}")
string(REGEX REPLACE "//[^\n]*" "" text "${text}")
string(REGEX MATCHALL "enum[ \t\r\n]+SegmentationMethod[ \t\r\n]*{[^}]*}" enums "${text}")
list(LENGTH enums count)
if(count EQUAL 0)
  uavmot_segmentation_methods_fail("${IDL}" "no such enum")
elseif(count GREATER 1)
  uavmot_segmentation_methods_fail("${IDL}" "the enum is defined ${count} times")
endif()
string(REGEX REPLACE "^enum[ \t\r\n]+SegmentationMethod[ \t\r\n]*{([^}]*)}$" "\\1" body "${enums}")
# An enumerator is followed by a comma, except perhaps the last.
string(REGEX REPLACE ",[ \t\r\n]*$" "" body "${body}")
if(body MATCHES "^[ \t\r\n]*$")
  uavmot_segmentation_methods_fail("${IDL}" "the enum lists no enumerator")
endif()
string(REPLACE "," ";" enumerators "${body}")

set(lines "")
set(seen "")
foreach(enumerator IN LISTS enumerators)
  string(STRIP "${enumerator}" enumerator)
  if(NOT enumerator MATCHES "^[A-Z][A-Z0-9]*(_[A-Z0-9]+)*$")
    uavmot_segmentation_methods_fail("${IDL}"
      "'${enumerator}' is not an UPPER_SNAKE_CASE enumerator without a value (a method's number is its place)")
  endif()
  if(enumerator IN_LIST seen)
    uavmot_segmentation_methods_fail("${IDL}" "'${enumerator}' is listed twice")
  endif()
  list(APPEND seen "${enumerator}")
  # name: lower case; C++ enumerator: each word capitalised, underscores dropped.
  string(TOLOWER "${enumerator}" name)
  string(REPLACE "_" ";" words "${name}")
  set(cpp "")
  foreach(word IN LISTS words)
    string(SUBSTRING "${word}" 0 1 first)
    string(SUBSTRING "${word}" 1 -1 rest)
    string(TOUPPER "${first}" first)
    string(APPEND cpp "${first}${rest}")
  endforeach()
  list(APPEND lines "  X(${cpp}, \"${name}\")")
endforeach()
list(JOIN lines " \\\n" lines)

get_filename_component(idl_name "${IDL}" NAME)
set(content "// Generated from ${idl_name} by cmake/segmentation_methods_from_idl.cmake; do not edit.
// X(enumerator, name) for every segmentation method, in wire order (the IDL's).
#define UAVMOT_SEGMENTATION_METHODS(X) \\
${lines}
")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL content)
  file(WRITE "${OUTPUT}" "${content}")
endif()
