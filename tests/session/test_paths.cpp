// The XDG folders: one rule for settings and worlds, including the spec's "a relative value is ignored".
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "session/paths.h"

namespace {

namespace fs = std::filesystem;

// Sets environment variables for one test and puts the old values back afterwards.
class Env {
public:
    void set(const char* name, const char* value) {
        remember(name);
        if (value) {
            ::setenv(name, value, 1);
        } else {
            ::unsetenv(name);
        }
    }
    ~Env() {
        for (const auto& [name, old] : m_saved) {
            if (old) {
                ::setenv(name.c_str(), old->c_str(), 1);
            } else {
                ::unsetenv(name.c_str());
            }
        }
    }

private:
    void remember(const char* name) {
        const char* old = std::getenv(name);
        m_saved.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
    }
    std::vector<std::pair<std::string, std::optional<std::string>>> m_saved;
};

TEST(XdgPaths, WorldsFollowXdgDataHomeThenHome) {
    Env env;
    env.set("HOME", "/home/u");
    env.set("XDG_DATA_HOME", "/data");
    EXPECT_EQ(session::defaultWorldsFolder(), fs::path("/data/minecrappy/worlds"));
    env.set("XDG_DATA_HOME", nullptr);
    EXPECT_EQ(session::defaultWorldsFolder(), fs::path("/home/u/.local/share/minecrappy/worlds"));
    env.set("XDG_DATA_HOME", "");
    EXPECT_EQ(session::defaultWorldsFolder(), fs::path("/home/u/.local/share/minecrappy/worlds"));
}

TEST(XdgPaths, ARelativeValueIsIgnoredForSettingsAndWorldsAlike) {
    Env env;
    env.set("HOME", "/home/u");
    env.set("XDG_DATA_HOME", "relative/data");
    env.set("XDG_CONFIG_HOME", "relative/config");
    EXPECT_EQ(session::defaultWorldsFolder(), fs::path("/home/u/.local/share/minecrappy/worlds"));
    EXPECT_EQ(session::defaultSettingsPath(), fs::path("/home/u/.config/minecrappy/settings.toml"));
}

TEST(XdgPaths, WithoutHomeTheWorkingFolderIsTheBase) {
    Env env;
    env.set("HOME", nullptr);
    env.set("XDG_CONFIG_HOME", nullptr);
    env.set("XDG_DATA_HOME", nullptr);
    EXPECT_EQ(session::defaultSettingsPath(), fs::path("./.config/minecrappy/settings.toml"));
    EXPECT_EQ(session::defaultWorldsFolder(), fs::path("./.local/share/minecrappy/worlds"));
}

} // namespace
