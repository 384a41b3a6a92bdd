// The exit codes of the `pge` command (also listed in `pge --help` and docs/commands.md).
#pragma once

namespace pge::cli {

inline constexpr int kExitOk = 0;           // the job ran and everything held
inline constexpr int kExitInternal = 1;     // an unexpected internal error (a bug: please report)
inline constexpr int kExitUsage = 2;        // bad command line
inline constexpr int kExitBadScene = 3;     // a scene file is unreadable, malformed or invalid
inline constexpr int kExitStorm = 4;        // a run stopped on an event storm
inline constexpr int kExitUnsupported = 5;  // a valid scene uses something not simulated yet
inline constexpr int kExitOutput = 6;       // an output file could not be written
inline constexpr int kExitCheckFailed = 7;  // `pge check` found a miss, a phantom, a tunnel, a time past the
                                            // solver's promise (promised_time_error_ulps) or a failed expectation;
                                            // `pge judge` found a miss or a phantom
inline constexpr int kExitInvariant = 8;    // an invariant failed: `pge fuzz` found a failing scene
inline constexpr int kExitGateFailed = 9;   // `pge gate`: accuracy or speed regressed past the baseline
inline constexpr int kExitBadResults = 10;  // report results or a baseline missing, unreadable or inconsistent
inline constexpr int kExitTunnel = 11;      // `pge run`: a moving body passed through a fixed body (tunnelling)
inline constexpr int kExitBadTrace = 12;    // `pge judge`: a trace file is unreadable, malformed or does not fit its scene

inline constexpr const char* kExitCodeHelp =
    "Exit codes: 0 ok; 1 internal error; 2 bad command line; 3 bad scene file;\n"
    "  4 event storm; 5 scene uses an unsupported feature; 6 cannot write output;\n"
    "  7 check found a miss, a phantom, a tunnel, a time past the solver's promise or a failed\n"
    "  expectation, or judge a miss or a phantom; 8 fuzz found a failing scene;\n"
    "  9 gate found a regression; 10 results or baseline missing or corrupt (the gate fails closed);\n"
    "  11 run found a body that passed through a fixed body (tunnelling);\n"
    "  12 judge was given a bad trace (unreadable, malformed, or not a run of the scene).";

}  // namespace pge::cli
