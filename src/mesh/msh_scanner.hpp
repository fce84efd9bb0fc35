#pragma once
// Private to the mesh module: the values of a Gmsh .msh 4.1 file held in memory, read either as
// ASCII tokens (one record per line, a token never crosses a line) or as little-endian binary,
// with bounds checks and errors naming the file, the section and the line (ASCII file) or the
// byte offset (binary file). Never reads past the end, never allocates from a file's count.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace emc::mesh::msh {

class Scanner {
 public:
  /// Scans `text` (the whole file); `where` ("<where>: '<file>'") prefixes every error.
  Scanner(const std::string& text, std::string where) : text_(text), where_(std::move(where)) {}

  /// Binary values from now on (a binary file's $Entities, $Nodes, $Elements), or ASCII.
  void set_binary(bool binary) { binary_ = binary; }
  bool binary() const { return binary_; }
  /// Errors of a binary file give byte offsets (its lines mean nothing), else line numbers.
  void set_binary_file(bool binary_file) { binary_file_ = binary_file; }
  /// The section named in errors ("" before the first one), as input::echo shows it (a
  /// corrupt header may hold any byte).
  void set_section(const std::string& section);

  /// True if only whitespace is left.
  bool at_end();
  /// Skips blanks, '\r' and newlines.
  void skip_space();
  /// The rest of the current line without trailing blanks and '\r'; moves past its newline.
  std::string line();
  /// Position in the file, and a move to a position found by the caller.
  std::size_t position() const { return pos_; }
  void seek(std::size_t pos) { pos_ = pos; }
  const std::string& text() const { return text_; }

  /// A size_t value (ASCII: an unsigned decimal; binary: 8 bytes).
  std::uint64_t size(const char* what);
  /// An int value (ASCII: a decimal in the range of int; binary: 4 bytes).
  int integer(const char* what);
  /// A double value (ASCII: a decimal number, NaN and inf included: callers check; binary: 8
  /// bytes).
  double real(const char* what);
  /// ASCII: refuses anything but blanks before the end of the line and moves past it. Binary:
  /// nothing (records are not lines).
  void end_line(const char* what);
  /// As end_line, but returns false (and stays) instead of refusing.
  bool try_end_line();
  /// ASCII: the text between double quotes, on the current line (a physical name).
  std::string quoted(const char* what);

  /// Refuses `count` records that the rest of the file cannot hold at `ascii_bytes` (a lower
  /// bound in an ASCII file) or `binary_bytes` (exact, binary) each; say, a count of 10^18.
  void check_count(std::uint64_t count, std::size_t ascii_bytes, std::size_t binary_bytes,
                   const std::string& what);

  /// Throws InputError "<where>: <location>: <what>".
  [[noreturn]] void fail(const std::string& what) const;
  /// Throws InputError "<where>: $<section>: <what>" (a problem of the section as a whole).
  [[noreturn]] void fail_section(const std::string& what) const;

  /// A token quoted for a message: at most 24 printable characters.
  static std::string quote(const std::string& token);

 private:
  const std::string& text_;
  std::string where_;
  std::string section_;
  std::size_t pos_ = 0;
  bool binary_ = false;
  bool binary_file_ = false;

  void skip_blanks();
  std::string token(const char* what);
  std::uint64_t little_endian(std::size_t bytes, const char* what);
  std::string location() const;
};

}  // namespace emc::mesh::msh
