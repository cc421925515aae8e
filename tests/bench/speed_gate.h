// The speed gate: ratios of the engine's hot paths against yardsticks built in the same process, which no
// change to the engine can move, checked against measured ceilings (tests/bench/speed_gate_ceilings.txt), so
// that a change that makes the mesher, the worker, light or the hair solver about twice as slow fails the
// test command. Run by `minecrappy-bench --gate` (docs/TESTING.md, "The speed gate").
#pragma once

namespace bench {

// minecrappy-bench --gate [--ceilings FILE] [--rounds N] [--only NAME] [--print]: returns 0 when every ratio
// is at most its ceiling (and the gate's own check that it fires passes), 1 when one is over, 2 for bad usage
// or a bad ceilings file. --print measures and prints without judging (for measuring ceilings).
int runSpeedGate(int argc, char** argv);

} // namespace bench
