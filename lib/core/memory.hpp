#pragma once
// Refusing a request that cannot fit before allocating it: a grid of 70000 x 70000 elements or a
// filter radius covering the whole domain must end in an error that says what it would need, not
// in an allocation of tens of GB that the operating system kills.
#include <cstdint>
#include <string_view>

namespace fem {

/// The machine's physical memory in bytes (0 when unknown).
std::uint64_t physical_memory_bytes();

/// Throws InputError "<what> needs about 350 GB of memory; this machine has 23 GB" when `bytes`
/// exceeds the memory available to the process: the physical memory, or less when a limit was set.
/// `what` names the request ("a 70000 x 70000 quad4 grid").
void require_memory(double bytes, std::string_view what);

/// Lowers the memory require_memory allows (bytes; 0 = the physical memory again). For programs that
/// run many inputs in one process under a budget, such as the fuzz targets (tests/fuzz).
void set_memory_limit(std::uint64_t bytes);

/// "350 GB", "12 MB": a byte count for messages.
std::string_view format_bytes(double bytes, char (&buffer)[32]);

}  // namespace fem
