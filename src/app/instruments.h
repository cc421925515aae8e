// What a headless run measures besides playing, attached to the runner through one interface so that the runner
// only runs: --frame-stats (a timed frame drawn after every tick, session::FrameStats) and --soak-report (each
// tick's CPU time and the pendulums' energy, session::SoakMonitor). The runner calls the hooks in order; an
// instrument that was not asked for is not made.
#pragma once
#include <memory>
#include <vector>

#include "app/frontend.h"
#include "render/context.h"
#include "session/options.h"
#include "session/session.h"

namespace app {

class Instrument {
public:
    virtual ~Instrument() = default;
    // Around the simulation of one tick (Session::step).
    virtual void beforeStep() {}
    virtual void afterStep(const session::Session&) {}
    // After the tick's own work (panels, screenshots asked for): may draw a frame of its own.
    virtual void afterTick(Frontend&, render::RenderContext&, const session::Session&) {}
    // Writes its report (throws core::OutputError or std::runtime_error naming the file); false when the run
    // failed what the instrument checks.
    virtual bool finish() = 0;
};

// The instruments the options ask for, set up on this session (the soak puts its methods into the sets).
std::vector<std::unique_ptr<Instrument>> makeInstruments(const session::Options& o, session::Session& session,
                                                         glm::ivec2 frameSize);

} // namespace app
