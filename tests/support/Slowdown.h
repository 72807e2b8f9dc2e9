// How much slower the build under test runs than a release build, for tests that bound a time.
#ifndef OSGLOA_TESTS_SLOWDOWN_H
#define OSGLOA_TESTS_SLOWDOWN_H 1

namespace loatest
{
/** 3 under AddressSanitizer (its allocator and checks: the 20,000-object CityJSON chain took
 *  2.8 s to refuse where a release build takes 0.6 s), else 1. */
#if defined(__SANITIZE_ADDRESS__)
constexpr double kSlowdown = 3.0;
#else
constexpr double kSlowdown = 1.0;
#endif
} // namespace loatest

#endif
