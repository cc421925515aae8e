// Writing a file so that the user's existing file is either replaced whole or left as it was: the bytes go
// to a temporary file beside the target (same folder, so the rename cannot cross file systems; a unique name,
// so two writers never share one), and only a successful commit renames it over the target. A writer that
// is destroyed without commit() (an exception, a refused run) removes its temporary file. Nothing ever
// leaves a half-written file under the target's name. Every writer of the game and the lab goes through here
// (settings, state dumps, screenshots, lab outputs); a new world file is the one exception, since it must
// never replace an existing file at all (save/world_store.cpp).
#pragma once
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>

namespace core {

class AtomicFile {
public:
    // Opens the temporary file; throws std::runtime_error naming `target` when that is impossible.
    explicit AtomicFile(std::filesystem::path target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return m_out; }
    const std::filesystem::path& target() const { return m_target; }

    // Flushes, closes and renames over the target; throws std::runtime_error naming the target when any
    // of that fails (disk full, folder removed meanwhile), after removing the temporary file.
    void commit();

private:
    std::filesystem::path m_target;
    std::filesystem::path m_temp;
    std::ofstream m_out;
    bool m_committed = false;
};

// For a writer that makes the file itself (a PNG encoder, a database): write(temp) writes the whole file at
// `temp` and returns false on failure; then the temporary file is renamed over `target`. Throws
// std::runtime_error naming `target` (after removing the temporary file) when writing or renaming fails.
void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<bool(const std::filesystem::path& temp)>& write);

} // namespace core
