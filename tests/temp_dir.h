// Fresh folders for the tests' files under the system's temporary folder, shared by every test folder.
#pragma once

#include <filesystem>
#include <random>
#include <string>

namespace test_util {

// Empties, or creates, the folder `leaf` under the system's temporary folder and returns its path.
inline std::filesystem::path freshTempDir(const std::string& leaf) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / leaf;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A fresh folder named `prefix`, `what`, "_" and a random number, so that test processes never share one.
inline std::filesystem::path freshRandomTempDir(const std::string& prefix, const std::string& what) {
    return freshTempDir(prefix + what + "_" + std::to_string(std::random_device{}()));
}

} // namespace test_util
