// Compiled into every executable of a sanitizer build only (cmake/SanitizerKeepModules.cmake).
//
// The Vulkan loader unloads the driver and the validation layer, and Open MPI its components, with
// dlclose() before the process exits. LeakSanitizer then meets the allocations those libraries keep
// for the process's life with no module name that ci/lsan.supp could match (`<unknown module>`),
// and the tests fail on leaks that are not ours. (The tracer crash this file was first written
// for has another cause: ci/sanitize.sh, intercept_tls_get_addr.) Defining dlclose()
// here interposes on libc's for every library in the process, so nothing is ever unloaded: the
// libraries' lifetime allocations keep their names (and are suppressed by them), and our own
// leaks stay reported. A product build never contains this file.
#include <dlfcn.h>

extern "C" int dlclose(void*) noexcept {
  return 0;
}
