// Keyframes and seeking (session/keyframes.h), in issue 48's scene: a 10-minute session at 60 Hz with four
// pendulum sets and ten default hair balls, most of them asleep most of the time (one spins: always awake), the
// player walking a loop past them and placing a block every half minute. Each round runs the session without
// keyframes and with them (every 30 ticks, the default budget), turn about, and times each tick's CPU; then, on
// the session with keyframes, seeks to random ticks and one tick back from random ticks. Prints the keyframes'
// share of the tick's CPU (the aim: at most 5 %), the memory they took and the spacing they ended at, and the
// seeks' median and worst (the aims: a tick back at most 50 ms, a seek 100 ms median and 500 ms worst).
//
//   build/minecrappy-bench --benchmark_filter=keyframeSession
//
// keyframeFileSeek records that session (its objects saved in a start world first) with the keyframe file
// (session/keyframe_file.h, the default interval), then, turn about over three rounds, seeks headless to minute 9
// in the replay with the file beside it and with the file moved away (replaying from the start world): to tick 32400,
// which has a keyframe, and to the tick before the next keyframe (the most stepping from a keyframe, 1799 ticks).
// Prints the file's size (its growth per 10 minutes) and the ratios of the seeks' times (the aim: at most 10 %).
//
//   build/minecrappy-bench --benchmark_filter=keyframeFileSeek
//
// timelineBackwards plays the first two minutes of that session backwards at 1x as the window does: each frame
// session::Timeline::advance by the frame's real time, then the scene drawn at radius 8 (1280x720, off-screen,
// finished), for ten seconds from the end. Prints the frames a second and the distinct ticks shown a second (the
// aim: at least 20).
//
//   build/minecrappy-bench --benchmark_filter=timelineBackwards
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/thread_clock.h"
#include "game/space.h"
#include "game/state_io.h"
#include "render/data_dir.h"
#include "render/offscreen.h"
#include "render/scene_renderer.h"
#include "session/session.h"
#include "session/timeline.h"

namespace {

constexpr std::uint64_t kTicks = 10 * 60 * 60;

// Three more sets and seven more balls (default shape, dftl) on free ground around the spawn point, placed by the
// placement rule.
void addObjects(game::GameState& s) {
    int sets = 0, balls = 0;
    const glm::ivec3 at(glm::floor(s.player.position));
    for (int ring = 6; ring < 40 && (sets < 3 || balls < 7); ring += 3) {
        for (int k = 0; k < 16 && (sets < 3 || balls < 7); ++k) {
            const float angle = 6.2831853f * static_cast<float>(k) / 16.0f + static_cast<float>(ring);
            const int x = at.x + static_cast<int>(std::lround(ring * std::cos(angle)));
            const int z = at.z + static_cast<int>(std::lround(ring * std::sin(angle)));
            const int ground = world::surfaceHeight(s.world.terrain(), x, z);
            if (sets < 3) {
                s.pendulumSets.emplace_back(glm::ivec3(x, ground + 1, z));
                if (game::placementProblem(s).empty()) {
                    ++sets;
                    continue;
                }
                s.pendulumSets.pop_back();
            }
            if (balls < 7) {
                s.hairBalls.emplace_back(glm::vec3(x + 0.5f, ground + 2.6f, z + 0.5f), game::HairBallDef{});
                if (game::placementProblem(s).empty()) {
                    ++balls;
                } else {
                    s.hairBalls.pop_back();
                }
            }
        }
    }
}

// The walk: W held, a quarter turn every 15 s, a jump every 7 s, a brick placed at the feet every 30 s.
std::string writeScript() {
    std::ostringstream out;
    out << "0 key W down\n";
    for (std::uint64_t t = 900; t < kTicks; t += 900) out << t << " mouse_move 600 0\n";
    for (std::uint64_t t = 420; t < kTicks; t += 420) out << t << " key SPACE down\n" << t + 2 << " key SPACE up\n";
    for (std::uint64_t t = 1800; t < kTicks; t += 1800)
        out << t << " key 7 down\n"
            << t + 1 << " key 7 up\n"
            << t + 2 << " mouse_move 0 800\n"
            << t + 3 << " mouse_button right down\n"
            << t + 4 << " mouse_button right up\n"
            << t + 5 << " mouse_move 0 -800\n";
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("mc_keyframe_bench_" + std::to_string(::getpid()) + ".txt");
    std::ofstream(path) << out.str();
    return path.string();
}

// A headless session with the built-in settings (no settings file read or written).
session::Options headlessOptions() {
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    return o;
}

struct Run {
    double tickCpuMs = 0.0;
    std::size_t bytes = 0, keyframes = 0;
    std::uint64_t interval = 0;
    std::vector<double> seekMs, backMs;
};

Run runSession(const std::string& script, bool keyframes, bool seeks) {
    session::Options o = headlessOptions();
    o.script = script;
    session::Session s(o);
    addObjects(s.state());
    if (s.state().pendulumSets.size() != 4 || s.state().hairBalls.size() != 10)
        throw std::runtime_error("the scene has " + std::to_string(s.state().pendulumSets.size()) + " sets and " +
                                 std::to_string(s.state().hairBalls.size()) + " balls, not the issue's 4 and 10");
    if (keyframes) s.keepKeyframes(session::KeyframeStore::kDefaultInterval, session::KeyframeStore::kDefaultBudget);
    Run r;
    const double start = core::threadCpuSeconds();
    for (std::uint64_t t = 0; t < kTicks; ++t) s.step();
    r.tickCpuMs = (core::threadCpuSeconds() - start) * 1e3 / static_cast<double>(kTicks);
    if (keyframes) {
        r.bytes = s.keyframes()->bytes();
        r.keyframes = s.keyframes()->size();
        r.interval = s.keyframes()->interval();
    }
    if (seeks) {
        std::mt19937_64 rng(48);
        const auto timed = [&](std::uint64_t tick) {
            const auto a = std::chrono::steady_clock::now();
            s.seek(tick);
            return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
        };
        for (int i = 0; i < 40; ++i) r.seekMs.push_back(timed(rng() % (kTicks + 1)));
        for (int i = 0; i < 40; ++i) {
            const std::uint64_t from = 1 + rng() % kTicks;
            s.seek(from);
            r.backMs.push_back(timed(from - 1));
        }
    }
    return r;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

void keyframeSession(benchmark::State& state) {
    const std::string script = writeScript();
    std::vector<double> without, with, ratio;
    Run last;
    for (auto _ : state) {
        for (int round = 0; round < 3; ++round) {
            const Run a = runSession(script, false, false);
            last = runSession(script, true, round == 2);
            without.push_back(a.tickCpuMs);
            with.push_back(last.tickCpuMs);
            ratio.push_back(last.tickCpuMs / a.tickCpuMs);
            std::printf("round %d: %.3f ms a tick without keyframes, %.3f with (%.3f)\n", round + 1, a.tickCpuMs,
                        last.tickCpuMs, last.tickCpuMs / a.tickCpuMs);
        }
        state.SetIterationTime(1.0);
    }
    std::filesystem::remove(script);
    const double seekMedian = median(last.seekMs),
                 seekWorst = *std::max_element(last.seekMs.begin(), last.seekMs.end());
    const double backMedian = median(last.backMs),
                 backWorst = *std::max_element(last.backMs.begin(), last.backMs.end());
    std::printf("keyframes: %zu kept, every %llu ticks, %.1f MiB; a tick %.3f / %.3f ms CPU (median ratio %.3f)\n"
                "seek: median %.1f ms, worst %.1f ms; one tick back: median %.1f ms, worst %.1f ms\n",
                last.keyframes, static_cast<unsigned long long>(last.interval),
                static_cast<double>(last.bytes) / (1 << 20), median(without), median(with), median(ratio), seekMedian,
                seekWorst, backMedian, backWorst);
    state.counters["keyframe_cost"] = median(ratio) - 1.0;
    state.counters["keyframes_MiB"] = static_cast<double>(last.bytes) / (1 << 20);
    state.counters["interval"] = static_cast<double>(last.interval);
    state.counters["seek_median_ms"] = seekMedian;
    state.counters["seek_worst_ms"] = seekWorst;
    state.counters["back_median_ms"] = backMedian;
    state.counters["back_worst_ms"] = backWorst;
}

double seekSeconds(const std::string& recording, std::uint64_t tick, std::uint64_t* hash) {
    const auto a = std::chrono::steady_clock::now();
    session::Options o = headlessOptions();
    o.script = recording;
    o.replay = true;
    session::Session s(o);
    s.seek(tick);
    *hash = game::stateHash(s.state());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

// Records `ticks` of the session (its objects saved in a start world first) into a fresh folder; returns the folder.
std::filesystem::path recordScene(const std::string& name, std::uint64_t ticks) {
    const std::string script = writeScript();
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("mc_" + name + "_bench_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string world = (dir / "scene.mcworld").string(), recording = (dir / "scene.mcscript").string();
    {
        session::Options o = headlessOptions();
        o.world = world;
        session::Session s(o);
        addObjects(s.state());
        if (!s.saveNow().empty()) throw std::runtime_error("cannot save " + world);
    }
    {
        session::Options o = headlessOptions();
        o.world = world;
        o.script = script;
        o.record = recording;
        session::Session s(o);
        if (s.state().pendulumSets.size() != 4 || s.state().hairBalls.size() != 10)
            throw std::runtime_error("the recorded scene is not the issue's");
        for (std::uint64_t t = 0; t < ticks; ++t) s.step();
        s.finishRecording();
    }
    std::filesystem::remove(script);
    return dir;
}

void keyframeFileSeek(benchmark::State& state) {
    const std::filesystem::path dir = recordScene("keyframe_file", kTicks);
    const std::string recording = (dir / "scene.mcscript").string();
    const std::filesystem::path keys = session::keyframeFilePath(recording), away = dir / "away.keys";
    const double fileMiB = static_cast<double>(std::filesystem::file_size(keys)) / (1 << 20);
    constexpr std::uint64_t kMinute9 = 9 * 60 * 60;
    const std::uint64_t targets[2] = {kMinute9, kMinute9 + session::kDefaultKeyframeFileInterval - 1};
    std::vector<double> withFile[2], fromStart[2], ratio[2];
    for (auto _ : state) {
        for (int round = 0; round < 3; ++round) {
            for (int k = 0; k < 2; ++k) {
                std::uint64_t a = 0, b = 0;
                withFile[k].push_back(seekSeconds(recording, targets[k], &a));
                std::filesystem::rename(keys, away);
                fromStart[k].push_back(seekSeconds(recording, targets[k], &b));
                std::filesystem::rename(away, keys);
                if (a != b) throw std::runtime_error("the seek from the file's keyframe reached another state");
                ratio[k].push_back(withFile[k].back() / fromStart[k].back());
                std::printf("round %d: --seek %llu with the keyframe file %.3f s, from the start world %.3f s (%.3f)\n",
                            round + 1, static_cast<unsigned long long>(targets[k]), withFile[k].back(),
                            fromStart[k].back(), ratio[k].back());
            }
        }
        state.SetIterationTime(1.0);
    }
    std::filesystem::remove_all(dir);
    std::printf("keyframe file: %.1f MiB for 10 minutes at 60 Hz (one keyframe every %d ticks)\n", fileMiB,
                session::kDefaultKeyframeFileInterval);
    for (int k = 0; k < 2; ++k)
        std::printf("--seek %llu: %.3f s with it, %.3f s without (median ratio %.3f)\n",
                    static_cast<unsigned long long>(targets[k]), median(withFile[k]), median(fromStart[k]),
                    median(ratio[k]));
    state.counters["file_MiB"] = fileMiB;
    state.counters["seek_ratio_at_keyframe"] = median(ratio[0]);
    state.counters["seek_ratio_worst"] = median(ratio[1]);
}

void timelineBackwards(benchmark::State& state) {
    const std::filesystem::path dir = recordScene("timeline", 2 * 60 * 60);
    session::Options o = headlessOptions();
    o.script = (dir / "scene.mcscript").string();
    o.replay = true;
    session::Session s(o);
    session::Timeline timeline(s, session::KeyframeStore::kDefaultInterval, session::KeyframeStore::kDefaultBudget);
    const glm::ivec2 size(1280, 720);
    const auto context = render::makeOffscreenContext(render::OffscreenBackend::Auto, size.x, size.y);
    render::SceneRenderer scene(render::dataDir());
    render::SceneSettings settings;
    settings.viewRadius = 8;
    const auto draw = [&] {
        scene.render(s.state(), render::interpolatedCamera(s.state(), 1.0f), size, settings, 1.0f);
        context->present();
    };
    timeline.jumpTo(timeline.lastTick()); // the first pass: every keyframe taken on the way
    while (timeline.catchingUp()) timeline.advance(0.0);
    for (int i = 0; i < 30; ++i) draw(); // the view loaded
    timeline.reverse();
    timeline.togglePlay();
    std::set<std::uint64_t> shown;
    int frames = 0;
    std::vector<double> frameMs;
    const std::uint64_t from = timeline.tick();
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        auto last = start;
        while (seconds < 10.0) {
            const auto now = std::chrono::steady_clock::now();
            timeline.advance(std::chrono::duration<double>(now - last).count());
            draw();
            const auto done = std::chrono::steady_clock::now();
            frameMs.push_back(std::chrono::duration<double, std::milli>(done - now).count());
            last = now;
            shown.insert(timeline.tick());
            ++frames;
            seconds = std::chrono::duration<double>(done - start).count();
        }
        state.SetIterationTime(seconds);
    }
    std::filesystem::remove_all(dir);
    std::printf("1x backwards from tick %llu to %llu in %.1f s: %.1f frames a second (median %.1f ms), %.1f distinct "
                "ticks shown a second (%s)\n",
                static_cast<unsigned long long>(from), static_cast<unsigned long long>(timeline.tick()), seconds,
                frames / seconds, median(frameMs), static_cast<double>(shown.size()) / seconds,
                std::string(render::currentOffscreenBackend()).c_str());
    state.counters["distinct_ticks_per_s"] = static_cast<double>(shown.size()) / seconds;
    state.counters["fps"] = frames / seconds;
}

} // namespace

BENCHMARK(timelineBackwards)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(keyframeFileSeek)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(keyframeSession)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
