// Saves a world without stalling the game: the main thread takes a snapshot (a plain copy, cheap) and
// hands it over; a worker thread writes it in one SQLite transaction. While a save is running only
// the newest waiting snapshot is kept, so a slow disk makes saves rarer, never the game slower.
// Failures (disk full, file deleted or made read-only) come back as messages; they never crash it.
#pragma once
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "save/world_store.h"

namespace session {

class Autosaver {
public:
    explicit Autosaver(std::unique_ptr<save::WorldStore> store);
    ~Autosaver(); // finishes the save in progress and the one waiting
    Autosaver(const Autosaver&) = delete;
    Autosaver& operator=(const Autosaver&) = delete;

    void submit(save::Snapshot snapshot);
    // Blocks until everything submitted is written; returns the errors since the last call.
    std::vector<std::string> flush();
    // Errors reported by the worker since the last call (non-blocking).
    std::vector<std::string> takeErrors();
    const std::filesystem::path& path() const { return m_path; }

private:
    void run();
    std::unique_ptr<save::WorldStore> m_store;
    std::filesystem::path m_path;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake, m_idle;
    std::optional<save::Snapshot> m_waiting;
    bool m_busy = false, m_stop = false;
    std::vector<std::string> m_errors;
    std::thread m_worker;
};

} // namespace session
