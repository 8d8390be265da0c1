#include "uavmot/core/app.hpp"

#include <malloc.h>

#include <cstring>
#include <iostream>

#include "uavmot/core/error.hpp"

namespace uavmot {

int run_app(int argc, char** argv, const std::string& name, const std::string& description, const AppSetup& setup) {
  if (argc == 2 && std::strcmp(argv[1], "--describe") == 0) {
    std::cout << description << "\n";
    return kExitOk;
  }
  // Frames are megabytes. By default glibc hands every freed buffer of that size back to the
  // kernel (mmap/munmap), so the next frame faults its pages in again: hundreds of page faults per
  // 1080p frame and copy, costly in a VM. Buffers up to 32 MB (the most glibc allows) come from
  // the heap instead, and up to 256 MB of free heap stays with the process.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  CLI::App app(description, "uavmot " + name);
  app.set_version_flag("--version", "uavmot 0.1.0");
  try {
    AppBody body = setup(app);
    app.parse(argc, argv);
    return body();
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
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
