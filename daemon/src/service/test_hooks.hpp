#pragma once
// Hooks for kewd's end-to-end tests (docs/testing.md). Their code is compiled only into
// builds with KEW_TEST_HOOKS (CMake: on with KEW_BUILD_TESTS, off in the Debian package),
// and only in test_hooks.cpp: the callers are the same objects in both builds (so the
// package's build shares them through ccache), and the shipped kewd calls empty
// functions, reading no test variable.

namespace kew::daemon::test_hooks {

/// Warns of every hook the environment sets.
void announce();
/// KEWD_TEST_STALL_FILE=PATH: while PATH exists, the pipeline's batch blocks, as a
/// worker that never returns would leave it, so that the watchdog's reaction can be
/// tested.
void maybe_stall_pipeline();

}  // namespace kew::daemon::test_hooks
