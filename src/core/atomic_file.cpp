#include "core/atomic_file.h"

#include <atomic>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace core {

namespace {
std::string uniqueSuffix() {
    // Two writers in one process (or two processes) aiming at the same folder must not share a name.
    static std::atomic<unsigned> counter{0};
    std::random_device rd;
    return std::to_string(rd()) + "-" + std::to_string(counter.fetch_add(1));
}

// ".NAME.tmp-RANDOM-COUNT" beside the target; throws for a target with no file name.
std::filesystem::path tempPathFor(const std::filesystem::path& target) {
    if (target.filename().empty()) throw std::runtime_error("cannot write '" + target.string() + "': not a file name");
    std::filesystem::path temp = target;
    // Built piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string tempName = ".";
    tempName += target.filename().string();
    tempName += ".tmp-";
    tempName += uniqueSuffix();
    temp.replace_filename(tempName);
    return temp;
}

// Renames temp over target, or removes temp and throws naming the target.
void renameOver(const std::filesystem::path& temp, const std::filesystem::path& target) {
    std::error_code ec;
    std::filesystem::rename(temp, target, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        throw std::runtime_error("cannot write '" + target.string() + "': " + ec.message());
    }
}
} // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : m_target(std::move(target)), m_temp(tempPathFor(m_target)) {
    m_out.open(m_temp, std::ios::binary | std::ios::trunc);
    if (!m_out) {
        throw std::runtime_error("cannot write '" + m_target.string() + "': cannot create a file in '" +
                                 m_target.parent_path().string() + "'");
    }
}

AtomicFile::~AtomicFile() {
    if (!m_committed) {
        m_out.close();
        std::error_code ec;
        std::filesystem::remove(m_temp, ec); // best effort; a destructor must not throw
    }
}

void AtomicFile::commit() {
    m_out.flush();
    const bool written = static_cast<bool>(m_out);
    m_out.close();
    std::error_code ec;
    if (!written || m_out.fail()) {
        std::filesystem::remove(m_temp, ec);
        throw std::runtime_error("cannot write '" + m_target.string() + "': write failed (disk full?)");
    }
    m_committed = true; // from here the temporary file is renamed or removed by renameOver
    renameOver(m_temp, m_target);
}

void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<bool(const std::filesystem::path& temp)>& write) {
    const std::filesystem::path temp = tempPathFor(target);
    bool written = false;
    try {
        written = write(temp);
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        throw;
    }
    if (!written) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        throw std::runtime_error("cannot write '" + target.string() + "': write failed");
    }
    renameOver(temp, target);
}

} // namespace core
