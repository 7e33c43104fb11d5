#include "core/memory.hpp"

#include <atomic>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "core/error.hpp"

namespace fem {

std::uint64_t physical_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

std::string_view format_bytes(double bytes, char (&buffer)[32]) {
    const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
    int u = 0;
    while (bytes >= 1000 && u < 6) bytes /= 1000, ++u;
    const int n = std::snprintf(buffer, sizeof buffer, "%.3g %s", bytes, units[u]);
    return {buffer, static_cast<std::size_t>(n)};
}

namespace {
std::atomic<std::uint64_t> memory_limit{0};
}

void set_memory_limit(std::uint64_t bytes) { memory_limit = bytes; }

void require_memory(double bytes, std::string_view what) {
    const std::uint64_t physical = physical_memory_bytes(), limit = memory_limit;
    const std::uint64_t have = limit > 0 && (physical == 0 || limit < physical) ? limit : physical;
    if (have == 0 || !(bytes > static_cast<double>(have))) return;
    char need_text[32], have_text[32];
    throw InputError(std::string(what) + " needs about " + std::string(format_bytes(bytes, need_text)) + " of memory; " +
                     (have == physical ? "this machine has " : "the limit set is ") +
                     std::string(format_bytes(static_cast<double>(have), have_text)));
}

}  // namespace fem
