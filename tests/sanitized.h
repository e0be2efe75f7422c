// Whether this test program is built with AddressSanitizer + UndefinedBehaviorSanitizer
// (scripts/sanitize.sh; cmake/Sanitizers.cmake defines STAIRPLAN_SANITIZED). Under them the code
// runs 5-30x slower, so a test whose full size takes minutes there runs fewer samples instead,
// asserting the same properties on them; the normal build always runs the full size.
#pragma once

namespace stairplan::testing {

#ifdef STAIRPLAN_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

/// `full` in the normal build, `sanitized` in the sanitizer build.
template <typename T>
constexpr T FullOrSanitized(T full, T sanitized) {
  return kSanitized ? sanitized : full;
}

}  // namespace stairplan::testing
