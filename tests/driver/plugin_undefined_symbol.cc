// A plugin library that needs a symbol no loaded library defines (built
// against another PeriDEAL, say): dlopen(RTLD_NOW) refuses it, and perideal
// must say so (shared_libraries.sh).

extern "C" double
perideal_test_function_that_nobody_defines(double);

double
perideal_test_plugin_value(const double x)
{
  return perideal_test_function_that_nobody_defines(x);
}
