#pragma once
// User text echoed in a message (a refused value, a file, body or surface name, a section header
// of a mesh file, the names a solver package did not know): short and printable, so that one
// message stays one short line (README "Messages stay short"). Every module that echoes user
// text uses these (the input module, whose library they are in, and the modules that link it).
#include <cstddef>
#include <string>
#include <vector>

namespace emc::input {

/// At most this many characters of an echoed text are shown.
constexpr std::size_t kEchoMax = 80;

/// `text` with its control bytes and DEL escaped (\n, \r, \t, \0 and \xNN for the others; a
/// NUL byte would otherwise end the message where it is printed), cut after kEchoMax characters
/// of the escaped text (not inside a UTF-8 sequence or an escape) with "... (N characters)", N
/// the length of `text`. Printable ASCII and UTF-8 are kept as they are.
std::string echo(const std::string& text);

/// At most `max_listed` of `names`, each echo()ed in double quotes, comma separated, then
/// " and N more" for the rest: "\"a\", \"b\" and 3 more".
std::string echo_list(const std::vector<std::string>& names, std::size_t max_listed = 5);

/// A number read from a file, for a message: "%.6g" ("1e+300", not 300 digits).
std::string echo_number(double value);

}  // namespace emc::input
