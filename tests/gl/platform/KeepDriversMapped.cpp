// AddressSanitizer builds only. LeakSanitizer looks for leaks when the process exits, after the EGL loader
// has unloaded Mesa's driver (eglTerminate → dlclose): the driver's process-lifetime allocations are then
// reported from an "unknown module" that tests/sanitizers/lsan.supp, which names the driver libraries, cannot
// match. Here dlclose keeps libraries mapped until exit, so the suppressions apply and a leak of our own is
// still reported with its stack. Only the context tests, which create and terminate several EGL displays,
// need it.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SYLVA_KEEP_DRIVERS_MAPPED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define SYLVA_KEEP_DRIVERS_MAPPED 1
#endif

#ifdef SYLVA_KEEP_DRIVERS_MAPPED
extern "C" int dlclose(void* /*handle*/) {
  return 0;
}
#endif
