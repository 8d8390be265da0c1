#include "uavmot/core/app.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>

#include <opencv2/core/utility.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/core/memory.hpp"

namespace uavmot {

namespace {

// A validator that refuses what is not a finite number inside `bound` ("> 0", "in [a - b]").
// CLI11's own PositiveNumber, NonNegativeNumber and Range let nan and inf through (every
// comparison with NaN is false).
CLI::Validator finite_number(std::function<bool(double)> inside, const std::string& bound, const std::string& type,
                             const std::string& name) {
  return CLI::Validator(
      [inside = std::move(inside), bound](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value)) return "not a number: " + text;
        if (!std::isfinite(value) || !inside(value)) return "not a finite number " + bound + ": " + text;
        return {};
      },
      type, name);
}

}  // namespace

CLI::Validator non_negative_finite() {
  return finite_number([](double v) { return v >= 0.0; }, ">= 0", "NONNEGATIVE", "NonNegativeFinite");
}
CLI::Validator positive_finite() {
  return finite_number([](double v) { return v > 0.0; }, "> 0", "POSITIVE", "PositiveFinite");
}

CLI::Validator finite_range(double low, double high) {
  std::ostringstream bounds;
  bounds << "[" << low << " - " << high << "]";
  return finite_number([low, high](double v) { return v >= low && v <= high; }, "in " + bounds.str(),
                       "FLOAT in " + bounds.str(), "FiniteRange");
}

CLI::Validator states_kept_check(const std::string& what) {
  constexpr long long kMostStatesKept = 1000000;
  return CLI::Validator(
      [what](std::string& value) -> std::string {
        try {
          size_t used = 0;
          const long long n = std::stoll(value, &used);
          if (used == value.size() && n >= 1 && n <= kMostStatesKept) return {};
        } catch (const std::exception&) {
        }
        return "'" + value + "' is not a number of saved " + what + " states (per stream) to keep: " +
               "give a whole number from 1 to " + std::to_string(kMostStatesKept);
      },
      "N>=1");
}

void apply_opencv_threads_from_environment() {
  const char* value = std::getenv("OPENCV_FOR_THREADS_NUM");
  if (value == nullptr || *value == '\0') return;
  char* end = nullptr;
  const long threads = std::strtol(value, &end, 10);
  if (*end != '\0' || threads < 1 || threads > 256) {
    std::cerr << "uavmot: warning: ignoring OPENCV_FOR_THREADS_NUM='" << value
              << "' (expected a whole number from 1 to 256); OpenCV keeps its default\n";
    return;
  }
  cv::setNumThreads(static_cast<int>(threads));
}

int run_app(int argc, char** argv, const std::string& name, const std::string& description, const AppSetup& setup) {
  if (argc == 2 && std::strcmp(argv[1], "--describe") == 0) {
    std::cout << description << "\n";
    return kExitOk;
  }
  configure_allocator_for_frames();
  apply_opencv_threads_from_environment();
  CLI::App app(description, "uavmot " + name);
  app.set_version_flag("--version", "uavmot 0.1.0");
  try {
    AppBody body = setup(app);
    app.parse(argc, argv);
    return body();
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every refused argument exits kExitBadInput like a bad
    // configuration file, not with CLI11's own codes (105, 106, ...).
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  } catch (const InputError& e) {
    std::cerr << "uavmot " << name << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const InvalidArgument& e) {
    std::cerr << "uavmot " << name << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "uavmot " << name << ": failed: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace uavmot
