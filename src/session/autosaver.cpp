#include "session/autosaver.h"

namespace session {

Autosaver::Autosaver(std::unique_ptr<save::WorldStore> store)
    : m_store(std::move(store)), m_path(m_store->path()), m_worker([this] { run(); }) {}

Autosaver::~Autosaver() {
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    m_worker.join();
}

void Autosaver::submit(save::Snapshot snapshot) {
    {
        std::lock_guard lock(m_mutex);
        m_waiting = std::move(snapshot);
    }
    m_wake.notify_all();
}

std::vector<std::string> Autosaver::flush() {
    std::unique_lock lock(m_mutex);
    m_idle.wait(lock, [this] { return !m_busy && !m_waiting; });
    std::vector<std::string> errors;
    errors.swap(m_errors);
    return errors;
}

std::vector<std::string> Autosaver::takeErrors() {
    std::lock_guard lock(m_mutex);
    std::vector<std::string> errors;
    errors.swap(m_errors);
    return errors;
}

void Autosaver::run() {
    std::unique_lock lock(m_mutex);
    for (;;) {
        m_wake.wait(lock, [this] { return m_stop || m_waiting.has_value(); });
        if (!m_waiting) break; // stopping with nothing left to write
        save::Snapshot snapshot = std::move(*m_waiting);
        m_waiting.reset();
        m_busy = true;
        lock.unlock();
        std::string error;
        try {
            m_store->save(snapshot);
        } catch (const std::exception& e) {
            error = e.what();
        }
        lock.lock();
        m_busy = false;
        if (!error.empty()) m_errors.push_back(error);
        m_idle.notify_all();
    }
    m_idle.notify_all();
}

} // namespace session
