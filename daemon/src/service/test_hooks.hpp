#pragma once
// Hooks for kewd's end-to-end tests (docs/testing.md), compiled only into builds with
// KEW_TEST_HOOKS (CMake: on with KEW_BUILD_TESTS, off in the Debian package): the
// shipped kewd reads no test variable and has none of this code.

namespace kew::daemon::test_hooks {

#if KEW_TEST_HOOKS
/// Warns of every hook the environment sets.
void announce();
/// KEWD_TEST_STALL_FILE=PATH: while PATH exists, the pipeline's batch blocks, as a
/// worker that never returns would leave it, so that the watchdog's reaction can be
/// tested.
void maybe_stall_pipeline();
#else
inline void announce() {}
inline void maybe_stall_pipeline() {}
#endif

}  // namespace kew::daemon::test_hooks
