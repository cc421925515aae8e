#include "lab/lab_cli.h"

#include "core/atomic_file.h"
#include "lab/hair_chain.h"
#include "lab/hair_charts.h"
#include "lab/hair_report.h"
#include "lab/hair_study.h"
#include "lab/lab_report.h"
#include "lab/lab_util.h"
#include "lab/long_run.h"
#include "lab/pendulum_common.h"
#include "lab/pendulum_run.h"
#include "lab/seed_figures.h"
#include "lab/stability.h"
#include "lab/stability_map.h"
#include "lab/work_precision.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <numbers>
#include <string>
#include <system_error>

namespace lab {

namespace {

constexpr const char* kProgram = "minecrappy-lab";

std::string methodList() {
    std::string out;
    for (int i = 0; i < physics::kMethodCount; ++i) {
        if (!out.empty()) out += ", ";
        out += physics::methodName(static_cast<physics::Method>(i));
    }
    return out;
}

// Reads the whole string as a double; false for trailing junk, an empty string or out-of-range text.
bool readDouble(const std::string& s, double& v) {
    if (s.empty()) return false;
    char* end = nullptr;
    v = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size();
}

CLI::Validator finiteNumber(bool positive, const char* unit) {
    return CLI::Validator(
        [positive, unit](std::string& s) -> std::string {
            double v = 0.0;
            if (!readDouble(s, v)) return "expected a number (" + std::string(unit) + "), got '" + s + "'";
            if (!std::isfinite(v)) return "expected a finite number (" + std::string(unit) + "), got '" + s + "'";
            if (positive && !(v > 0.0)) return "must be > 0 (" + std::string(unit) + "), got '" + s + "'";
            return {};
        },
        positive ? "POSITIVE" : "NUMBER");
}

const CLI::Validator kMethodName(
    [](std::string& s) -> std::string {
        return physics::methodFromName(s) ? std::string()
                                          : "unknown method '" + s + "'; valid methods: " + methodList();
    },
    "METHOD");

struct PendulumArgs {
    std::string method;
    double dt = 0.0;
    double theta0Deg = 0.0;
    double omega0 = 0.0;
    double length = 1.0;
    double gravity = 9.81;
    double mass = 1.0;
    double seconds = 0.0;
    double tolerance = physics::kDefaultDopri5Tolerance;
    std::string csv;
};

// False (after a message naming `flag`, e.g. --csv, and `command`) when the file `path` cannot be written: the
// name is a folder, or its folder does not exist.
bool outputPathUsable(const std::string& path, const std::string& flag, const std::string& command, std::ostream& err) {
    const std::filesystem::path file(path);
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) {
        err << kProgram << " " << command << ": " << flag << ": '" << path << "' is a folder; give a file name\n";
        return false;
    }
    const auto parent = file.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
        err << kProgram << " " << command << ": " << flag << ": the folder '" << parent.string()
            << "' does not exist\n";
        return false;
    }
    return true;
}

// Writes `body` to the file `path` given with `flag` (e.g. --csv) whole, or not at all; false (after a message
// naming the flag) when the name is a folder or its folder does not exist.
bool writeOutputFile(const std::string& path, const std::string& flag, const std::string& command, std::ostream& err,
                     const std::function<void(std::ostream&)>& body) {
    if (!outputPathUsable(path, flag, command, err)) return false;
    core::AtomicFile out{std::filesystem::path(path)};
    body(out.stream());
    out.commit();
    return true;
}

int runPendulum(const PendulumArgs& a, std::ostream& out, std::ostream& err) {
    PendulumRun run;
    run.method = *physics::methodFromName(a.method);
    run.params.length = a.length;
    run.params.gravity = a.gravity;
    run.params.mass = a.mass;
    run.initial = {a.theta0Deg * std::numbers::pi / 180.0, a.omega0};
    run.dt = a.dt;
    run.seconds = a.seconds;
    run.tolerance = a.tolerance;
    const std::int64_t steps = stepCount(run.seconds, run.dt);
    if (steps < 0 || steps > kMaxSteps) {
        err << kProgram << " pendulum: --seconds / --dt asks for "
            << (steps < 0 ? std::string("too many") : std::to_string(steps)) << " steps; at most " << kMaxSteps
            << " are allowed (use a larger --dt or a shorter --seconds)\n";
        return 2;
    }
    if (const std::string why = validateRun(run); !why.empty()) {
        err << kProgram << " pendulum: " << why << "\n";
        return 2;
    }
    if (!outputPathUsable(a.csv, "--csv", "pendulum", err)) return 2;
    const std::filesystem::path csv(a.csv);
    try {
        writePendulumCsv(run, csv);
    } catch (const std::invalid_argument& e) { // parameters the physics refuses (none expected after validation)
        err << kProgram << " pendulum: " << e.what() << "\n";
        return 2;
    }
    out << "pendulum: wrote " << csv.string() << " (" << steps + 1 << " rows, " << a.method << ", dt = " << a.dt
        << " s)\n";
    return 0;
}

// A study that prints its result and, given --json FILE, writes it there too (hair-bench, hair-check): checks
// `o` with `validate`, runs it with `run`, prints it with `print` and writes the file with `writeJson`.
template <class Options, class Validate, class Run, class Print, class WriteJson>
int runJsonStudy(const std::string& command, const Options& o, Validate validate, Run run, Print print,
                 WriteJson writeJson, const std::string& json, std::ostream& out, std::ostream& err) {
    if (const std::string why = validate(o); !why.empty()) {
        err << kProgram << " " << command << ": " << why << "\n";
        return 2;
    }
    const auto r = run(o);
    print(r, out);
    if (!json.empty()) {
        if (!writeOutputFile(json, "--json", command, err, [&](std::ostream& s) { writeJson(r, s); })) return 2;
        out << command << ": wrote " << json << "\n";
    }
    return 0;
}

int runHairChainCommand(const HairChainOptions& o, const std::string& csv, std::ostream& out, std::ostream& err) {
    if (const std::string why = validateHairChain(o); !why.empty()) {
        err << kProgram << " hair-chain: " << why << "\n";
        return 2;
    }
    const std::vector<HairChainRow> rows = runHairChain(o);
    if (!writeOutputFile(csv, "--csv", "hair-chain", err, [&](std::ostream& s) { writeHairChainCsv(rows, s); }))
        return 2;
    const HairChainRow& last = rows.back();
    out << "hair-chain: wrote " << csv << " (" << rows.size() << " rows, " << o.solver << ", " << o.links
        << " links, dt = " << o.dt << " s); tip error at t = " << last.t << " s: " << last.tipError << " m\n";
    return 0;
}

// Every command's flags, filled by parsing.
struct LabArgs {
    PendulumArgs pa;
    std::string wpOut, stOut, sfOut;
    int mapAngles = 90, mapSteps = 80;
    HairBenchOptions hb;
    std::string hbJson;
    HairCheckOptions hc;
    std::string hcJson;
    HairChainOptions hch;
    std::string hchCsv;
    std::string hwpOut, hstOut;
    bool hwpQuick = false, hstQuick = false;
    std::string longOut;
    LongRunOptions longRun;
    std::string reportOut;
    int reportRuns = 5;
};

struct LabCommands {
    CLI::App *pendulum = nullptr, *workPrecision = nullptr, *stability = nullptr, *seed = nullptr, *longRun = nullptr;
    CLI::App *hairBench = nullptr, *hairCheck = nullptr, *hairChain = nullptr, *hairWorkPrecision = nullptr,
             *hairStability = nullptr, *hairReport = nullptr, *report = nullptr;
};

void addPendulumCommand(CLI::App& cli, LabArgs& a, LabCommands& c) {
    c.pendulum = cli.add_subcommand("pendulum", "Run one pendulum and write every step as CSV: "
                                                "t,theta,omega,energy,theta_exact,energy_error");
    c.pendulum->add_option("--method", a.pa.method, "Integrator: " + methodList())->required()->check(kMethodName);
    c.pendulum->add_option("--dt", a.pa.dt, "Step (s), > 0")->required()->check(finiteNumber(true, "seconds"));
    c.pendulum->add_option("--theta0", a.pa.theta0Deg, "Initial angle from straight down (degrees), |theta0| <= 5.7e7")
        ->required()
        ->check(finiteNumber(false, "degrees"))
        ->check(CLI::Range(-physics::kMaxInitialAngle * 180.0 / std::numbers::pi,
                           physics::kMaxInitialAngle * 180.0 / std::numbers::pi));
    c.pendulum
        ->add_option("--omega0", a.pa.omega0, "Initial angular velocity (rad/s), finite; |omega0| <= 1e6 sqrt(g/L)")
        ->capture_default_str()
        ->check(finiteNumber(false, "rad/s"));
    c.pendulum->add_option("--length", a.pa.length, "Rod length (m), in [0.001, 16] (the game's rods)")
        ->capture_default_str()
        ->check(finiteNumber(true, "metres"))
        ->check(CLI::Range(physics::kMinPendulumLength, physics::kMaxPendulumLength));
    c.pendulum->add_option("--g", a.pa.gravity, "Gravity (m/s^2), in (0, 1e4] (the game's gravities)")
        ->capture_default_str()
        ->check(finiteNumber(true, "m/s^2"))
        ->check(CLI::Range(0.0, physics::kMaxPendulumGravity));
    c.pendulum->add_option("--mass", a.pa.mass, "Bob mass (kg), in (0, 1e6]; scales the energy column only")
        ->capture_default_str()
        ->check(finiteNumber(true, "kg"))
        ->check(CLI::Range(0.0, kMaxLabMass));
    c.pendulum->add_option("--seconds", a.pa.seconds, "Simulated time (s), > 0; at most 50 million steps")
        ->required()
        ->check(finiteNumber(true, "seconds"));
    c.pendulum
        ->add_option("--tolerance", a.pa.tolerance,
                     "dopri5's error tolerance (absolute and relative), in [1e-14, 1]; --dt is then its output step, "
                     "rows interpolated by its dense output, with a steps column")
        ->capture_default_str()
        ->check(finiteNumber(true, "a tolerance"));
    c.pendulum->add_option("--csv", a.pa.csv, "Output CSV file (replaced whole, or left as it was on failure)")
        ->required();
}

// A study command that writes its files into the folder given with --out (required).
CLI::App* addStudyCommand(CLI::App& cli, const std::string& name, const std::string& help, std::string& outDir) {
    CLI::App* command = cli.add_subcommand(name, help);
    command->add_option("--out", outDir, "Output folder (created if missing)")->required();
    return command;
}

void addPendulumStudies(CLI::App& cli, LabArgs& a, LabCommands& c) {
    c.workPrecision =
        addStudyCommand(cli, "work-precision",
                        "Every integrator at 16 steps from 0.1 ms to 100 ms, released from 60 degrees: angle error "
                        "at 10 s and energy error over 60 s against force evaluations and measured time. Writes "
                        "work_precision.csv and work_precision.svg (about 10 s).",
                        a.wpOut);
    c.stability = addStudyCommand(
        cli, "stability",
        "First omega0*dt that does not stay bounded for 60 s, per fixed-step integrator and release angle "
        "(10, 60, 120, 170, 179 degrees), on a grid 0.1 % apart from a bounded step, with the islands "
        "above it and a grid-sensitivity check on a 10 times finer grid; then a map per integrator of "
        "bounded cells, release angle against omega0*dt, with the first failure at each angle on the "
        "same 0.1 % grid. Writes stability.csv, stability_islands.csv, stability.svg, "
        "stability_map.csv, stability_map_limits.csv and stability_map.svg (minutes: see docs/LAB.md).",
        a.stOut);
    c.stability
        ->add_option("--map-angles", a.mapAngles, "Release angles in the map, evenly spaced from 1 to 179 degrees")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000));
    c.stability->add_option("--map-steps", a.mapSteps, "omega0*dt values in the map, log-spaced from 0.01 to 4")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000));
    c.seed =
        addStudyCommand(cli, "seed-figures",
                        "The seed write-up's plots done right: theta, omega and energy over 20 s at dt = 1, 16 and "
                        "33 ms for euler, euler-cartesian, midpoint and trapezoid against the exact solution. Writes "
                        "seed_dt<N>ms.svg and .csv.",
                        a.sfOut);
}

// --solver, --iterations and --substeps, as hair-bench and hair-check take them.
void addHairSolverOptions(CLI::App& command, std::string& solver, int& iterations, int& substeps) {
    command.add_option("--solver", solver, "Hair solver: " + physics::hairMethodNames())->capture_default_str();
    command
        .add_option("--iterations", iterations,
                    "Constraint passes (shake: Newton iterations) per substep; 0 = the game's default")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    command.add_option("--substeps", substeps, "Substeps per step; 0 = the game's default")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
}

void addHairCommands(CLI::App& cli, LabArgs& a, LabCommands& c) {
    c.hairBench = cli.add_subcommand(
        "hair-bench", "Time the hair solver (ball collision on) beside a naive seed-style reference and a minimal "
                      "vectorised kernel (the machine's practical limit), in one run; prints a summary, --json writes "
                      "node_steps_per_s, naive_node_steps_per_s, limit_node_steps_per_s, ms_per_step, threads.");
    c.hairBench->add_option("--strands", a.hb.strands, "Strands on the ball")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxHairStrands));
    c.hairBench->add_option("--nodes", a.hb.nodes, "Nodes per strand, root included")
        ->capture_default_str()
        ->check(CLI::Range(2, kMaxHairNodesPerStrand));
    addHairSolverOptions(*c.hairBench, a.hb.solver, a.hb.iterations, a.hb.substeps);
    c.hairBench->add_option("--steps", a.hb.steps, "Timed steps")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxHairSteps));
    c.hairBench->add_option("--threads", a.hb.threads, "Threads for the solver")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxHairThreads));
    c.hairBench->add_option("--json", a.hbJson, "Also write the figures as JSON to this file");

    c.hairCheck = cli.add_subcommand(
        "hair-check",
        "Drive a hair ball through spin, carry (with a 0.25 s frame spike) and a drop onto blocks, "
        "then let it rest; prints JSON: solver, iterations, substeps, dt, max_segment_error, max_penetration, nan, "
        "settle_seconds, rest_settle_seconds.");
    addHairSolverOptions(*c.hairCheck, a.hc.solver, a.hc.iterations, a.hc.substeps);
    c.hairCheck->add_option("--dt", a.hc.dt, "Step (s), in (0, 1]")
        ->capture_default_str()
        ->check(finiteNumber(true, "seconds"));
    c.hairCheck->add_option("--seconds", a.hc.seconds, "Length of each phase (s), in (0, 600]")
        ->capture_default_str()
        ->check(finiteNumber(true, "seconds"));
    c.hairCheck->add_option("--json", a.hcJson, "Also write the JSON to this file");

    c.hairChain = cli.add_subcommand(
        "hair-chain", "Release a straight horizontal strand (no damping, no collider, root pinned) in the hair "
                      "solver and in the exact N-link chain (Dormand-Prince 5(4), tolerance 1e-12); writes every "
                      "step as CSV: t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error.");
    c.hairChain->add_option("--solver", a.hch.solver, "Hair method: " + physics::hairMethodNames() + ", or reference")
        ->capture_default_str();
    c.hairChain->add_option("--links", a.hch.links, "Links (free nodes), 1..64")->capture_default_str();
    c.hairChain->add_option("--length", a.hch.length, "Strand length (m), in (0, 10]")->capture_default_str();
    c.hairChain->add_option("--dt", a.hch.dt, "Step (s), in (0, 1]")->capture_default_str();
    c.hairChain->add_option("--seconds", a.hch.seconds, "Simulated time (s), in (0, 600]; at most 1,000,000 steps")
        ->capture_default_str();
    c.hairChain->add_option("--iterations", a.hch.iterations, "Iterations a substep, 0..1000; 0 = the method's default")
        ->capture_default_str();
    c.hairChain->add_option("--substeps", a.hch.substeps, "Substeps a step, 0..1000; 0 = the method's default")
        ->capture_default_str();
    c.hairChain->add_flag(
        "--auto-substeps", a.hch.automaticSubsteps,
        "Automatic substeps as in the game: steps over 1/60 s split, shake's from its segments' turn");
    c.hairChain->add_option("--csv", a.hchCsv, "Output CSV file (replaced whole, or left as it was on failure)")
        ->required();

    c.hairWorkPrecision = addStudyCommand(
        cli, "hair-work-precision",
        "Every hair method over steps 1/30 to 1/240 s and its iterations or substeps, on the 11-link chain against "
        "its exact reference (and shake with automatic substeps, at the cost of the substeps it took): tip error at "
        "0.5 s and 2 s, largest segment and energy errors, and past the horizon (2.5 to 10 s) the mean energy, the "
        "tip's mean height and swing period beside the reference's, against measured ns per node-step and "
        "projections per node. Writes hair_work_precision.csv and .svg (about 20 s).",
        a.hwpOut);
    c.hairWorkPrecision->add_flag("--quick", a.hwpQuick, "A small sweep (seconds; for tests)");
    c.hairStability =
        addStudyCommand(cli, "hair-stability",
                        "For each hair method at the game's settings, the largest step, spin rate and carry speed "
                        "at which a ball stays bounded (no NaN, no node beyond its strand, none inside a collider, "
                        "segment error under 5 %), islands included. Writes hair_stability.csv, "
                        "hair_stability_limits.csv and hair_stability.svg.",
                        a.hstOut);
    c.hairStability->add_flag("--quick", a.hstQuick, "A small scan (seconds; for tests)");

    c.hairReport = cli.add_subcommand(
        "hair-report", "Print, as Markdown, the hair figures docs/HAIR.md quotes (the chain against its exact "
                       "solution for every method, hair-check and its drop distributions at 30, 60, 144 and 240 Hz, "
                       "the chains' horizons and what the eye sees past them); a test holds docs/HAIR.md to them. "
                       "About 40 s.");
}

// long-run and report, the last two in --help.
void addLongRunAndReport(CLI::App& cli, LabArgs& a, LabCommands& c) {
    c.longRun = addStudyCommand(
        cli, "long-run",
        "Each integrator's largest energy error in log-spaced windows over 20,000 s at dt = 50, 16.7 and 5 "
        "ms, released from 60 degrees: which methods drift, which stay bounded, and the leapfrog "
        "midpoint's parasitic growth. Writes long_run.csv (method,dt,window_end_s,max_energy_error) and "
        "long_run.svg (about 5 s).",
        a.longOut);
    c.longRun->add_option("--seconds", a.longRun.seconds, "Simulated time (s), > 0; at most 50 million steps a run")
        ->capture_default_str()
        ->check(finiteNumber(true, "seconds"));
    c.longRun
        ->add_option("--theta0", a.longRun.theta0Deg, "Release angle from straight down (degrees), |theta0| <= 5.7e7")
        ->capture_default_str()
        ->check(finiteNumber(false, "degrees"))
        ->check(CLI::Range(-physics::kMaxInitialAngle * 180.0 / std::numbers::pi,
                           physics::kMaxInitialAngle * 180.0 / std::numbers::pi));

    c.report = addStudyCommand(
        cli, "report",
        "Write report.md: the lab and hair tables of docs/LAB.md and docs/HAIR.md as Markdown, each with the "
        "command that makes "
        "its full version (the deterministic blocks between the markers the docs' tests compare), then "
        "the step timings with the CPU and the spread of several runs. About a minute.",
        a.reportOut);
    c.report->add_option("--timing-runs", a.reportRuns, "Runs of the timing table, 0..50 (0: leave it out)")
        ->capture_default_str()
        ->check(CLI::Range(0, 50));
}

// Runs `study` and tells `err` how many `what` it made and in how long: "COMMAND: N WHAT in S s".
template <class Study>
auto timedStudy(const std::string& command, const std::string& what, std::ostream& err, Study study) {
    const auto start = std::chrono::steady_clock::now();
    auto points = study();
    err << command << ": " << points.size() << " " << what << " in " << secondsSince(start) << " s\n";
    return points;
}

int runLongRunCommand(const LabArgs& a, std::ostream& out, std::ostream& err, const Progress& toErr) {
    if (const std::string why = validateLongRun(a.longRun); !why.empty()) {
        err << kProgram << " long-run: " << why << "\n";
        return 2;
    }
    if (!prepareOutDir(a.longOut, "long-run", err)) return 2;
    const auto points = timedStudy("long-run", "windows", err, [&] { return runLongRun(a.longRun, toErr); });
    reportWritten(out, "long-run", writeLongRun(points, a.longRun, a.longOut));
    return 0;
}

int runReportCommand(const LabArgs& a, const std::string& versionLine, std::ostream& out, std::ostream& err,
                     const Progress& toErr) {
    if (!prepareOutDir(a.reportOut, "report", err)) return 2;
    std::string md = "# Minecrappy lab report\n\nMade by `" + versionLine + " report`.\n\n## Pendulum\n\n";
    toErr("report: pendulum figures");
    md += "<!-- lab-report:begin -->\n" + pendulumReportMarkdown() + "<!-- lab-report:end -->\n\n## Hair\n\n";
    toErr("report: hair figures");
    md += "`minecrappy-lab hair-report`:\n\n<!-- hair-report:begin -->\n" + hairReportMarkdown() +
          "<!-- hair-report:end -->\n";
    if (a.reportRuns > 0) {
        toErr("report: timings (" + std::to_string(a.reportRuns) + " runs)");
        md += "\n## Timings\n\n" + timingReportMarkdown(a.reportRuns);
    }
    const std::filesystem::path file = std::filesystem::path(a.reportOut) / "report.md";
    core::AtomicFile f(file);
    f.stream() << md;
    f.commit();
    reportWritten(out, "report", {file});
    return 0;
}

int runWorkPrecisionCommand(const LabArgs& a, std::ostream& out, std::ostream& err, const Progress& toErr) {
    if (!prepareOutDir(a.wpOut, "work-precision", err)) return 2;
    const WorkPrecisionOptions options;
    const auto points = timedStudy("work-precision", "runs", err, [&] { return runWorkPrecision(options, toErr); });
    reportWritten(out, "work-precision", writeWorkPrecision(points, options, a.wpOut));
    return 0;
}

int runStabilityCommand(const LabArgs& a, std::ostream& out, std::ostream& err, const Progress& toErr) {
    if (!prepareOutDir(a.stOut, "stability", err)) return 2;
    const StabilityOptions options;
    const auto points = timedStudy("stability", "limits", err, [&] { return runStability(options, toErr); });
    StabilityMapOptions mapOptions;
    mapOptions.angleCount = a.mapAngles;
    mapOptions.omegaDtCount = a.mapSteps;
    const auto maps = runStabilityMaps(mapOptions, toErr);
    std::vector<std::filesystem::path> written = writeStability(points, options, a.stOut);
    for (const auto& p : writeStabilityMaps(maps, mapOptions, a.stOut, points)) written.push_back(p);
    reportWritten(out, "stability", written);
    return 0;
}

int runSeedFiguresCommand(const LabArgs& a, std::ostream& out, std::ostream& err, const Progress& toErr) {
    if (!prepareOutDir(a.sfOut, "seed-figures", err)) return 2;
    const SeedFiguresOptions options;
    const auto figures = runSeedFigures(options, toErr);
    reportWritten(out, "seed-figures", writeSeedFigures(figures, options, a.sfOut));
    return 0;
}

// The parsed command, run; -1 when none was given.
int runParsed(const LabCommands& c, const LabArgs& a, const std::string& versionLine, std::ostream& out,
              std::ostream& err) {
    const Progress toErr = [&err](const std::string& line) { err << line << "\n" << std::flush; };
    if (c.pendulum->parsed()) return runPendulum(a.pa, out, err);
    if (c.hairBench->parsed())
        return runJsonStudy("hair-bench", a.hb, validateHairBench, runHairBench, writeHairBenchSummary,
                            writeHairBenchJson, a.hbJson, out, err);
    if (c.hairCheck->parsed())
        return runJsonStudy("hair-check", a.hc, validateHairCheck, runHairCheck, writeHairCheckJson, writeHairCheckJson,
                            a.hcJson, out, err);
    if (c.hairChain->parsed()) return runHairChainCommand(a.hch, a.hchCsv, out, err);
    if (c.hairWorkPrecision->parsed()) return runHairWorkPrecisionCommand(a.hwpOut, a.hwpQuick, out, err);
    if (c.hairStability->parsed()) return runHairStabilityCommand(a.hstOut, a.hstQuick, out, err);
    if (c.hairReport->parsed()) {
        out << hairReportMarkdown();
        return 0;
    }
    if (c.longRun->parsed()) return runLongRunCommand(a, out, err, toErr);
    if (c.report->parsed()) return runReportCommand(a, versionLine, out, err, toErr);
    if (c.workPrecision->parsed()) return runWorkPrecisionCommand(a, out, err, toErr);
    if (c.stability->parsed()) return runStabilityCommand(a, out, err, toErr);
    if (c.seed->parsed()) return runSeedFiguresCommand(a, out, err, toErr);
    return -1;
}

} // namespace

int runLab(int argc, const char* const* argv, std::ostream& out, std::ostream& err, std::string_view version) {
    CLI::App cli{"minecrappy-lab: physics studies without graphics (pendulum integrators: single runs, "
                 "work-precision, stability, the seed write-up's figures).\n"
                 "Run 'minecrappy-lab COMMAND --help' for a command's flags, or --help-all for all of them.",
                 kProgram};
    cli.set_help_all_flag("--help-all", "Print the help of every command");
    const std::string versionLine = std::string(kProgram) + " " + std::string(version);
    if (!version.empty()) cli.set_version_flag("--version", versionLine);
    cli.require_subcommand(0, 1);

    LabArgs a;
    LabCommands c;
    // In the order --help lists them.
    addPendulumCommand(cli, a, c);
    addPendulumStudies(cli, a, c);
    addHairCommands(cli, a, c);
    addLongRunAndReport(cli, a, c);

    try {
        cli.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out << cli.help();
        return 0;
    } catch (const CLI::CallForAllHelp&) {
        out << cli.help("", CLI::AppFormatMode::All);
        return 0;
    } catch (const CLI::CallForVersion&) {
        out << versionLine << "\n";
        return 0;
    } catch (const CLI::ParseError& e) {
        err << kProgram << ": " << e.what() << "\nRun with --help for the commands and their flags.\n";
        return 2;
    }
    try {
        if (const int rc = runParsed(c, a, versionLine, out, err); rc >= 0) return rc;
    } catch (const core::OutputError& e) {
        // An output the rule refuses or the system would not take (a full disk): as in the game, exit 2.
        err << kProgram << ": " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        err << kProgram << ": " << e.what() << "\n";
        return 1;
    }
    out << cli.help();
    return 0;
}

int runLab(int argc, char** argv, std::string_view version) {
    return runLab(argc, argv, std::cout, std::cerr, version);
}

} // namespace lab
