// minecrappy-lab: the physics without graphics. Its studies (pendulum integrators, hair) arrive as
// subcommands; until then it answers --help and --version and rejects anything else with exit code 2.
#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App cli{"minecrappy-lab: physics studies without graphics (sweeps, charts, benchmarks).\n"
                 "No studies are available in this version yet.",
                 "minecrappy-lab"};
    cli.set_version_flag("--version", std::string("minecrappy-lab ") + MC_VERSION);
    cli.require_subcommand(0, 1);
    try {
        cli.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::fputs(cli.help().c_str(), stdout);
        return 0;
    } catch (const CLI::CallForVersion&) {
        std::printf("minecrappy-lab %s\n", MC_VERSION);
        return 0;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "minecrappy-lab: %s\nRun with --help for the commands.\n", e.what());
        return 2;
    }
    std::fputs(cli.help().c_str(), stdout);
    return 0;
}
