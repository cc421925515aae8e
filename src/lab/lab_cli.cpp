#include "lab/lab_cli.h"

#include "core/atomic_file.h"
#include "lab/hair_chain.h"
#include "lab/hair_charts.h"
#include "lab/hair_report.h"
#include "lab/hair_study.h"
#include "lab/lab_report.h"
#include "lab/lab_util.h"
#include "lab/long_run.h"
#include "lab/pendulum_study.h"

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
    const std::filesystem::path csv(a.csv);
    std::error_code ec;
    if (std::filesystem::is_directory(csv, ec)) {
        err << kProgram << " pendulum: --csv: '" << a.csv << "' is a folder; give a file name\n";
        return 2;
    }
    const auto parent = csv.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
        err << kProgram << " pendulum: --csv: the folder '" << parent.string() << "' does not exist\n";
        return 2;
    }
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

// Writes `body` to --json FILE whole (or not at all); false (after a message naming --json) when it cannot.
bool writeJson(const std::string& path, const std::string& command, std::ostream& err,
               const std::function<void(std::ostream&)>& body) {
    const std::filesystem::path file(path);
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) {
        err << kProgram << " " << command << ": --json: '" << path << "' is a folder; give a file name\n";
        return false;
    }
    const auto parent = file.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
        err << kProgram << " " << command << ": --json: the folder '" << parent.string() << "' does not exist\n";
        return false;
    }
    core::AtomicFile out(file);
    body(out.stream());
    out.commit();
    return true;
}

int runHairBenchCommand(const HairBenchOptions& o, const std::string& json, std::ostream& out, std::ostream& err) {
    if (const std::string why = validateHairBench(o); !why.empty()) {
        err << kProgram << " hair-bench: " << why << "\n";
        return 2;
    }
    const HairBenchResult r = runHairBench(o);
    writeHairBenchSummary(r, out);
    if (!json.empty()) {
        if (!writeJson(json, "hair-bench", err, [&](std::ostream& s) { writeHairBenchJson(r, s); })) return 2;
        out << "hair-bench: wrote " << json << "\n";
    }
    return 0;
}

int runHairCheckCommand(const HairCheckOptions& o, const std::string& json, std::ostream& out, std::ostream& err) {
    if (const std::string why = validateHairCheck(o); !why.empty()) {
        err << kProgram << " hair-check: " << why << "\n";
        return 2;
    }
    const HairCheckResult r = runHairCheck(o);
    writeHairCheckJson(r, out);
    if (!json.empty()) {
        if (!writeJson(json, "hair-check", err, [&](std::ostream& s) { writeHairCheckJson(r, s); })) return 2;
        out << "hair-check: wrote " << json << "\n";
    }
    return 0;
}

// Writes `body` to the file `path` given with `flag` (e.g. --csv) whole, or not at all; false (after a message
// naming the flag) when the name is a folder or its folder does not exist.
bool writeOutputFile(const std::string& path, const std::string& flag, const std::string& command, std::ostream& err,
                     const std::function<void(std::ostream&)>& body) {
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
    core::AtomicFile out(file);
    body(out.stream());
    out.commit();
    return true;
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

    PendulumArgs pa;
    CLI::App* pendulum = cli.add_subcommand("pendulum", "Run one pendulum and write every step as CSV: "
                                                        "t,theta,omega,energy,theta_exact,energy_error");
    pendulum->add_option("--method", pa.method, "Integrator: " + methodList())->required()->check(kMethodName);
    pendulum->add_option("--dt", pa.dt, "Step (s), > 0")->required()->check(finiteNumber(true, "seconds"));
    pendulum->add_option("--theta0", pa.theta0Deg, "Initial angle from straight down (degrees), |theta0| <= 5.7e7")
        ->required()
        ->check(finiteNumber(false, "degrees"))
        ->check(CLI::Range(-physics::kMaxInitialAngle * 180.0 / std::numbers::pi,
                           physics::kMaxInitialAngle * 180.0 / std::numbers::pi));
    pendulum->add_option("--omega0", pa.omega0, "Initial angular velocity (rad/s), finite; |omega0| <= 1e6 sqrt(g/L)")
        ->capture_default_str()
        ->check(finiteNumber(false, "rad/s"));
    pendulum->add_option("--length", pa.length, "Rod length (m), in [0.001, 16] (the game's rods)")
        ->capture_default_str()
        ->check(finiteNumber(true, "metres"))
        ->check(CLI::Range(physics::kMinPendulumLength, physics::kMaxPendulumLength));
    pendulum->add_option("--g", pa.gravity, "Gravity (m/s^2), in (0, 1e4] (the game's gravities)")
        ->capture_default_str()
        ->check(finiteNumber(true, "m/s^2"))
        ->check(CLI::Range(0.0, physics::kMaxPendulumGravity));
    pendulum->add_option("--mass", pa.mass, "Bob mass (kg), in (0, 1e6]; scales the energy column only")
        ->capture_default_str()
        ->check(finiteNumber(true, "kg"))
        ->check(CLI::Range(0.0, kMaxLabMass));
    pendulum->add_option("--seconds", pa.seconds, "Simulated time (s), > 0; at most 50 million steps")
        ->required()
        ->check(finiteNumber(true, "seconds"));
    pendulum
        ->add_option("--tolerance", pa.tolerance,
                     "dopri5's error tolerance (absolute and relative), in [1e-14, 1]; --dt is then its output step, "
                     "rows interpolated by its dense output, with a steps column")
        ->capture_default_str()
        ->check(finiteNumber(true, "a tolerance"));
    pendulum->add_option("--csv", pa.csv, "Output CSV file (replaced whole, or left as it was on failure)")->required();

    std::string wpOut, stOut, sfOut;
    CLI::App* workPrecision = cli.add_subcommand(
        "work-precision", "Every integrator at 16 steps from 0.1 ms to 100 ms, released from 60 degrees: angle error "
                          "at 10 s and energy error over 60 s against force evaluations and measured time. Writes "
                          "work_precision.csv and work_precision.svg (about 10 s).");
    workPrecision->add_option("--out", wpOut, "Output folder (created if missing)")->required();
    CLI::App* stability = cli.add_subcommand(
        "stability", "First omega0*dt that does not stay bounded for 60 s, per fixed-step integrator and release angle "
                     "(10, 60, 120, 170, 179 degrees), on a grid 0.1 % apart from a bounded step, with the islands "
                     "above it and a grid-sensitivity check on a 10 times finer grid; then a map per integrator of "
                     "bounded cells, release angle against omega0*dt, with the first failure at each angle on the "
                     "same 0.1 % grid. Writes stability.csv, stability_islands.csv, stability.svg, "
                     "stability_map.csv, stability_map_limits.csv and stability_map.svg (minutes: see docs/LAB.md).");
    stability->add_option("--out", stOut, "Output folder (created if missing)")->required();
    int mapAngles = 90, mapSteps = 80;
    stability->add_option("--map-angles", mapAngles, "Release angles in the map, evenly spaced from 1 to 179 degrees")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000));
    stability->add_option("--map-steps", mapSteps, "omega0*dt values in the map, log-spaced from 0.01 to 4")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000));
    CLI::App* seed = cli.add_subcommand(
        "seed-figures", "The seed write-up's plots done right: theta, omega and energy over 20 s at dt = 1, 16 and "
                        "33 ms for euler, euler-cartesian, midpoint and trapezoid against the exact solution. Writes "
                        "seed_dt<N>ms.svg and .csv.");
    seed->add_option("--out", sfOut, "Output folder (created if missing)")->required();

    HairBenchOptions hb;
    std::string hbJson;
    CLI::App* hairBench = cli.add_subcommand(
        "hair-bench", "Time the hair solver (ball collision on) beside a naive seed-style reference and a minimal "
                      "vectorised kernel (the machine's practical limit), in one run; prints a summary, --json writes "
                      "node_steps_per_s, naive_node_steps_per_s, limit_node_steps_per_s, ms_per_step, threads.");
    hairBench->add_option("--strands", hb.strands, "Strands on the ball")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxHairStrands));
    hairBench->add_option("--nodes", hb.nodes, "Nodes per strand, root included")
        ->capture_default_str()
        ->check(CLI::Range(2, kMaxHairNodesPerStrand));
    hairBench->add_option("--solver", hb.solver, "Hair solver: " + physics::hairMethodNames())->capture_default_str();
    hairBench
        ->add_option("--iterations", hb.iterations,
                     "Constraint passes (shake: Newton iterations) per substep; 0 = the game's default")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    hairBench->add_option("--substeps", hb.substeps, "Substeps per step; 0 = the game's default")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    hairBench->add_option("--steps", hb.steps, "Timed steps")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxHairSteps));
    hairBench->add_option("--threads", hb.threads, "Threads for the solver")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxHairThreads));
    hairBench->add_option("--json", hbJson, "Also write the figures as JSON to this file");

    HairCheckOptions hc;
    std::string hcJson;
    CLI::App* hairCheck = cli.add_subcommand(
        "hair-check",
        "Drive a hair ball through spin, carry (with a 0.25 s frame spike) and a drop onto blocks, "
        "then let it rest; prints JSON: solver, iterations, substeps, dt, max_segment_error, max_penetration, nan, "
        "settle_seconds, rest_settle_seconds.");
    hairCheck->add_option("--solver", hc.solver, "Hair solver: " + physics::hairMethodNames())->capture_default_str();
    hairCheck
        ->add_option("--iterations", hc.iterations,
                     "Constraint passes (shake: Newton iterations) per substep; 0 = the game's default")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    hairCheck->add_option("--substeps", hc.substeps, "Substeps per step; 0 = the game's default")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    hairCheck->add_option("--dt", hc.dt, "Step (s), in (0, 1]")
        ->capture_default_str()
        ->check(finiteNumber(true, "seconds"));
    hairCheck->add_option("--seconds", hc.seconds, "Length of each phase (s), in (0, 600]")
        ->capture_default_str()
        ->check(finiteNumber(true, "seconds"));
    hairCheck->add_option("--json", hcJson, "Also write the JSON to this file");

    HairChainOptions hch;
    std::string hchCsv;
    CLI::App* hairChain = cli.add_subcommand(
        "hair-chain", "Release a straight horizontal strand (no damping, no collider, root pinned) in the hair "
                      "solver and in the exact N-link chain (Dormand-Prince 5(4), tolerance 1e-12); writes every "
                      "step as CSV: t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error.");
    hairChain->add_option("--solver", hch.solver, "Hair method: " + physics::hairMethodNames() + ", or reference")
        ->capture_default_str();
    hairChain->add_option("--links", hch.links, "Links (free nodes), 1..64")->capture_default_str();
    hairChain->add_option("--length", hch.length, "Strand length (m), in (0, 10]")->capture_default_str();
    hairChain->add_option("--dt", hch.dt, "Step (s), in (0, 1]")->capture_default_str();
    hairChain->add_option("--seconds", hch.seconds, "Simulated time (s), in (0, 600]; at most 1,000,000 steps")
        ->capture_default_str();
    hairChain->add_option("--iterations", hch.iterations, "Iterations a substep, 0..1000; 0 = the method's default")
        ->capture_default_str();
    hairChain->add_option("--substeps", hch.substeps, "Substeps a step, 0..1000; 0 = the method's default")
        ->capture_default_str();
    hairChain->add_flag("--auto-substeps", hch.automaticSubsteps,
                        "Automatic substeps as in the game: steps over 1/60 s split, shake's from its segments' turn");
    hairChain->add_option("--csv", hchCsv, "Output CSV file (replaced whole, or left as it was on failure)")
        ->required();

    std::string hwpOut, hstOut;
    bool hwpQuick = false, hstQuick = false;
    CLI::App* hairWorkPrecision = cli.add_subcommand(
        "hair-work-precision",
        "Every hair method over steps 1/30 to 1/240 s and its iterations or substeps, on the 11-link chain against "
        "its exact reference (and shake with automatic substeps, at the cost of the substeps it took): tip error at "
        "0.5 s and 2 s, largest segment and energy errors, and past the horizon (2.5 to 10 s) the mean energy, the "
        "tip's mean height and swing period beside the reference's, against measured ns per node-step and "
        "projections per node. Writes hair_work_precision.csv and .svg (about 20 s).");
    hairWorkPrecision->add_option("--out", hwpOut, "Output folder (created if missing)")->required();
    hairWorkPrecision->add_flag("--quick", hwpQuick, "A small sweep (seconds; for tests)");
    CLI::App* hairStability = cli.add_subcommand(
        "hair-stability", "For each hair method at the game's settings, the largest step, spin rate and carry speed "
                          "at which a ball stays bounded (no NaN, no node beyond its strand, none inside a collider, "
                          "segment error under 5 %), islands included. Writes hair_stability.csv, "
                          "hair_stability_limits.csv and hair_stability.svg.");
    hairStability->add_option("--out", hstOut, "Output folder (created if missing)")->required();
    hairStability->add_flag("--quick", hstQuick, "A small scan (seconds; for tests)");

    CLI::App* hairReport = cli.add_subcommand(
        "hair-report", "Print, as Markdown, the hair figures docs/HAIR.md quotes (the chain against its exact "
                       "solution for every method, hair-check and its drop distributions at 30, 60, 144 and 240 Hz, "
                       "the chains' horizons and what the eye sees past them); a test holds docs/HAIR.md to them. "
                       "About 40 s.");

    std::string longOut;
    LongRunOptions longRun;
    CLI::App* longRunCommand = cli.add_subcommand(
        "long-run", "Each integrator's largest energy error in log-spaced windows over 20,000 s at dt = 50, 16.7 and 5 "
                    "ms, released from 60 degrees: which methods drift, which stay bounded, and the leapfrog "
                    "midpoint's parasitic growth. Writes long_run.csv (method,dt,window_end_s,max_energy_error) and "
                    "long_run.svg (about 5 s).");
    longRunCommand->add_option("--out", longOut, "Output folder (created if missing)")->required();
    longRunCommand->add_option("--seconds", longRun.seconds, "Simulated time (s), > 0; at most 50 million steps a run")
        ->capture_default_str()
        ->check(finiteNumber(true, "seconds"));
    longRunCommand
        ->add_option("--theta0", longRun.theta0Deg, "Release angle from straight down (degrees), |theta0| <= 5.7e7")
        ->capture_default_str()
        ->check(finiteNumber(false, "degrees"))
        ->check(CLI::Range(-physics::kMaxInitialAngle * 180.0 / std::numbers::pi,
                           physics::kMaxInitialAngle * 180.0 / std::numbers::pi));

    std::string reportOut;
    int reportRuns = 5;
    CLI::App* report = cli.add_subcommand(
        "report", "Write report.md: the lab and hair tables of docs/LAB.md and docs/HAIR.md as Markdown, each with the "
                  "command that makes "
                  "its full version (the deterministic blocks between the markers the docs' tests compare), then "
                  "the step timings with the CPU and the spread of several runs. About a minute.");
    report->add_option("--out", reportOut, "Output folder (created if missing)")->required();
    report->add_option("--timing-runs", reportRuns, "Runs of the timing table, 0..50 (0: leave it out)")
        ->capture_default_str()
        ->check(CLI::Range(0, 50));

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

    const auto toErr = [&err](const std::string& line) { err << line << "\n" << std::flush; };
    try {
        if (pendulum->parsed()) return runPendulum(pa, out, err);
        if (hairBench->parsed()) return runHairBenchCommand(hb, hbJson, out, err);
        if (hairCheck->parsed()) return runHairCheckCommand(hc, hcJson, out, err);
        if (hairChain->parsed()) return runHairChainCommand(hch, hchCsv, out, err);
        if (hairWorkPrecision->parsed()) return runHairWorkPrecisionCommand(hwpOut, hwpQuick, out, err);
        if (hairStability->parsed()) return runHairStabilityCommand(hstOut, hstQuick, out, err);
        if (hairReport->parsed()) {
            out << hairReportMarkdown();
            return 0;
        }
        if (longRunCommand->parsed()) {
            if (const std::string why = validateLongRun(longRun); !why.empty()) {
                err << kProgram << " long-run: " << why << "\n";
                return 2;
            }
            if (!prepareOutDir(longOut, "long-run", err)) return 2;
            const auto start = std::chrono::steady_clock::now();
            const auto points = runLongRun(longRun, toErr);
            err << "long-run: " << points.size() << " windows in " << secondsSince(start) << " s\n";
            reportWritten(out, "long-run", writeLongRun(points, longRun, longOut));
            return 0;
        }
        if (report->parsed()) {
            if (!prepareOutDir(reportOut, "report", err)) return 2;
            std::string md = "# Minecrappy lab report\n\nMade by `" + versionLine + " report`.\n\n## Pendulum\n\n";
            toErr("report: pendulum figures");
            md += "<!-- lab-report:begin -->\n" + pendulumReportMarkdown() + "<!-- lab-report:end -->\n\n## Hair\n\n";
            toErr("report: hair figures");
            md += "`minecrappy-lab hair-report`:\n\n<!-- hair-report:begin -->\n" + hairReportMarkdown() +
                  "<!-- hair-report:end -->\n";
            if (reportRuns > 0) {
                toErr("report: timings (" + std::to_string(reportRuns) + " runs)");
                md += "\n## Timings\n\n" + timingReportMarkdown(reportRuns);
            }
            const std::filesystem::path file = std::filesystem::path(reportOut) / "report.md";
            core::AtomicFile f(file);
            f.stream() << md;
            f.commit();
            reportWritten(out, "report", {file});
            return 0;
        }
        if (workPrecision->parsed()) {
            if (!prepareOutDir(wpOut, "work-precision", err)) return 2;
            const WorkPrecisionOptions options;
            const auto start = std::chrono::steady_clock::now();
            const auto points = runWorkPrecision(options, toErr);
            err << "work-precision: " << points.size() << " runs in " << secondsSince(start) << " s\n";
            reportWritten(out, "work-precision", writeWorkPrecision(points, options, wpOut));
            return 0;
        }
        if (stability->parsed()) {
            if (!prepareOutDir(stOut, "stability", err)) return 2;
            const StabilityOptions options;
            const auto start = std::chrono::steady_clock::now();
            const auto points = runStability(options, toErr);
            err << "stability: " << points.size() << " limits in " << secondsSince(start) << " s\n";
            StabilityMapOptions mapOptions;
            mapOptions.angleCount = mapAngles;
            mapOptions.omegaDtCount = mapSteps;
            const auto maps = runStabilityMaps(mapOptions, toErr);
            std::vector<std::filesystem::path> written = writeStability(points, options, stOut);
            for (const auto& p : writeStabilityMaps(maps, mapOptions, stOut, points)) written.push_back(p);
            reportWritten(out, "stability", written);
            return 0;
        }
        if (seed->parsed()) {
            if (!prepareOutDir(sfOut, "seed-figures", err)) return 2;
            const SeedFiguresOptions options;
            const auto figures = runSeedFigures(options, toErr);
            reportWritten(out, "seed-figures", writeSeedFigures(figures, options, sfOut));
            return 0;
        }
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
