// The game-state fuzzer's harness (tests/fuzz/game_fuzz.h) in the Release build: its corpus (seeds and every
// input a fuzzing run found, tests/fuzz/corpus/game) and a seeded stream of random inputs. The libFuzzer run
// of the same harness is fuzz.game in the sanitizer build.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "../fuzz/game_fuzz.h"
#include "core/rng.h"

namespace {

TEST(GameFuzz, EveryCorpusInputKeepsTheInvariantsAndRoundTrips) {
    const std::filesystem::path dir = std::filesystem::path(MC_TEST_DATA) / "fuzz" / "corpus" / "game";
    int inputs = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        SCOPED_TRACE(entry.path().string());
        gamefuzz::runOne(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        ++inputs;
    }
    EXPECT_GE(inputs, 3) << "precondition: the corpus is there";
}

TEST(GameFuzz, SeededRandomInputsKeepTheInvariantsAndRoundTrip) {
    core::Rng rng(20261123);
    for (int i = 0; i < 300; ++i) {
        std::vector<std::uint8_t> bytes(1 + rng.next() % 256);
        for (auto& b : bytes) b = static_cast<std::uint8_t>(rng.next());
        gamefuzz::runOne(bytes.data(), bytes.size());
    }
}

// The harness is only as good as the scripts it writes: they reach the game (the player moves and looks), and
// the two failures the issue names are among what it produces.
TEST(GameFuzz, DecodedScriptsParseAndCoverTheCommands) {
    core::Rng rng(7);
    std::string all;
    for (int i = 0; i < 200; ++i) {
        std::vector<std::uint8_t> bytes(64);
        for (auto& b : bytes) b = static_cast<std::uint8_t>(rng.next());
        all += gamefuzz::decode(bytes.data(), bytes.size()).script;
    }
    EXPECT_NO_THROW(input::parseScript(all, "all.script"));
    for (const char* command : {" key ", " mouse_move ", " mouse_button ", " scroll ", " gamepad_axis ",
                                " gamepad_button ", " teleport ", " look ", "e+38"})
        EXPECT_NE(all.find(command), std::string::npos) << command;
}

} // namespace
