// Bounded reads of the files a user or an earlier run hands in (lists, summaries, captures): only
// a regular file is read (a FIFO blocks the reader, a device such as /dev/zero never ends), and
// only up to a cap stated by the caller, checked against the file's size before reading and again
// while reading (a file that grows). Bad input names the file and what was expected (InputError).
#pragma once

#include <cstdint>
#include <istream>
#include <string>

namespace rastercmp {

// Throws InputError unless `path` (links followed) is a regular file of at most `max_bytes`;
// `what` names the file's role in the message, e.g. "a baseline file".
void check_bounded_file(const std::string& path, uint64_t max_bytes, const std::string& what);

// Reads `in` to its end but at most max_bytes + 1 bytes: a longer (or endless) stream shows as a
// result longer than max_bytes. The caller checks in.bad() for a read error.
std::string read_at_most(std::istream& in, uint64_t max_bytes);

// The whole file, after check_bounded_file.
std::string read_bounded_file(const std::string& path, uint64_t max_bytes, const std::string& what);

}  // namespace rastercmp
