#include "lab/lab_util.h"

#include "core/atomic_file.h"

#include <charconv>
#include <cstdio>
#include <system_error>

namespace lab {

void appendNumber(std::string& line, double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    line.append(buf, r.ptr);
}

std::string formatNumber(const char* printfFormat, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, printfFormat, v);
    return buf;
}

std::string formatShort(double v) { return formatNumber("%.4g", v); }

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::filesystem::path writeCsvFile(const std::filesystem::path& path, const std::function<void(std::ostream&)>& body) {
    core::AtomicFile file(path);
    body(file.stream());
    file.commit();
    return path;
}

bool prepareOutDir(const std::string& dir, const std::string& command, std::ostream& err) {
    if (const std::string link = core::brokenLinkOnPath(dir); !link.empty()) {
        err << "minecrappy-lab " << command << ": --out: cannot make the folder '" << dir << "': " << link << "\n";
        return false;
    }
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir, ec)) {
        err << "minecrappy-lab " << command << ": --out: cannot create the folder '" << dir
            << "': " << (ec ? ec.message() : std::string("a file of that name is in the way")) << "\n";
        return false;
    }
    return true;
}

void reportWritten(std::ostream& out, const std::string& command, const std::vector<std::filesystem::path>& paths) {
    for (const auto& p : paths) out << command << ": wrote " << p.string() << "\n";
}

} // namespace lab
