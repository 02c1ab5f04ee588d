// Ctrl-C while a device is driven: the handler only sets a flag (async-signal-safe); the servo
// tick that sees it sends zero force and stops its loop, and the run stops after its step.
#pragma once

namespace filum::haptics {

/// Installs the SIGINT and SIGTERM handler (once; later calls do nothing).
void installInterruptHandler();
/// Whether Ctrl-C (or SIGTERM) arrived since the handler was installed.
bool interruptRequested();
/// Clears the flag (tests).
void clearInterrupt();

}  // namespace filum::haptics
