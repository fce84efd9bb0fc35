// Reading the XML input: a strict scan of the values, then Teuchos' reader.
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <set>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/input/files.hpp"

namespace emc::input::detail {
namespace {

[[noreturn]] void cannot_read(const std::string& file, const std::string& reason) {
  throw InputError(file + ": cannot read the input: " + reason);
}

/// Deeper nesting than this is refused before Teuchos' recursive reader sees it (deep enough
/// nesting overflows its stack); real inputs nest 4 or 5 levels.
constexpr int kMaxDepth = 64;

/// The deepest element nesting of the XML text (comments, processing instructions,
/// declarations, CDATA and quoted attribute values skipped), or kMaxDepth + 1 once beyond.
int nesting_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  for (std::size_t i = text.find('<'); i != std::string::npos; i = text.find('<', i)) {
    auto skip_past = [&](const char* end) {
      const auto e = text.find(end, i);
      i = e == std::string::npos ? text.size() : e + std::strlen(end);
    };
    if (text.compare(i, 4, "<!--") == 0) {
      skip_past("-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      skip_past("]]>");
    } else if (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0) {
      skip_past(">");
    } else if (text.compare(i, 2, "</") == 0) {
      --depth;
      skip_past(">");
    } else {  // a start tag: find its end outside quoted attribute values
      char quote = 0;
      std::size_t j = i + 1;
      for (; j < text.size(); ++j) {
        if (quote) {
          if (text[j] == quote) quote = 0;
        } else if (text[j] == '"' || text[j] == '\'') {
          quote = text[j];
        } else if (text[j] == '>') {
          break;
        }
      }
      if (j >= text.size() || text[j - 1] != '/') deepest = std::max(deepest, ++depth);
      if (deepest > kMaxDepth) return deepest;
      i = j;
    }
  }
  return deepest;
}

/// The encoding a byte order mark at the start of `text` announces, or "" if none other than
/// UTF-8's.
std::string other_encoding(const std::string& text) {
  const auto starts = [&](std::initializer_list<unsigned char> bom) {
    if (text.size() < bom.size()) return false;
    std::size_t i = 0;
    for (const unsigned char b : bom)
      if (static_cast<unsigned char>(text[i++]) != b) return false;
    return true;
  };
  if (starts({0x00, 0x00, 0xfe, 0xff}) || starts({0xff, 0xfe, 0x00, 0x00})) return "UTF-32";
  if (starts({0xfe, 0xff}) || starts({0xff, 0xfe})) return "UTF-16";
  return "";
}

/// The offset of the first byte of `text` that does not begin a well-formed UTF-8 sequence
/// (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or npos.
std::size_t first_invalid_utf8(const std::string& text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char b = byte(i);
    std::size_t n = 0;                   // continuation bytes
    unsigned char lo = 0x80, hi = 0xbf;  // the second byte's range
    if (b < 0x80) {
      ++i;
      continue;
    } else if (b >= 0xc2 && b <= 0xdf) {
      n = 1;
    } else if (b >= 0xe0 && b <= 0xef) {
      n = 2;
      if (b == 0xe0) lo = 0xa0;
      if (b == 0xed) hi = 0x9f;
    } else if (b >= 0xf0 && b <= 0xf4) {
      n = 3;
      if (b == 0xf0) lo = 0x90;
      if (b == 0xf4) hi = 0x8f;
    } else {
      return i;
    }
    if (i + n >= text.size()) return i;  // cut short
    for (std::size_t k = 1; k <= n; ++k) {
      const unsigned char c = byte(i + k);
      if (c < (k == 1 ? lo : 0x80) || c > (k == 1 ? hi : 0xbf)) return i;
    }
    i += n + 1;
  }
  return std::string::npos;
}

/// The 1-based line of byte `at` of `text`.
std::size_t line_of(const std::string& text, std::size_t at) {
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
}

/// The text of the input as UTF-8 without its byte order mark (which Teuchos' parser refuses).
/// Refuses UTF-16 and UTF-32 (a byte order mark, or NUL bytes, which UTF-8 text never holds).
std::string utf8_text(std::string text, const std::string& file) {
  const std::string how = "; it must be UTF-8 (or ASCII) text: convert it, e.g. iconv -f ";
  const std::string encoding = other_encoding(text);
  if (!encoding.empty())
    cannot_read(file,
                "it is " + encoding + " text (a byte order mark)" + how + encoding + " -t UTF-8");
  const auto nul = text.find('\0');
  if (nul != std::string::npos)
    cannot_read(file, "it holds a NUL byte (byte " + std::to_string(nul) +
                          "): not text, or UTF-16" + how + "UTF-16 -t UTF-8");
  const auto bad = first_invalid_utf8(text);
  if (bad != std::string::npos) {
    const std::string hex = format("0x%02x", static_cast<unsigned char>(text[bad]));
    cannot_read(file, "byte " + std::to_string(bad) + " (line " +
                          std::to_string(line_of(text, bad)) + ", " + hex + ") is not UTF-8" + how +
                          "ISO-8859-1 -t UTF-8 (if that is its encoding)");
  }
  if (text.compare(0, 3, "\xef\xbb\xbf") == 0) text.erase(0, 3);  // UTF-8's byte order mark
  return text;
}

/// Refuses XML text nested too deeply.
void check_depth(const std::string& file, const std::string& text) {
  if (nesting_depth(text) > kMaxDepth)
    cannot_read(file, "elements are nested more than " + std::to_string(kMaxDepth) +
                          " levels deep (the limit; an input needs about 5)");
}

/// A type-appropriate example of what a value must look like.
std::string value_hint(const std::string& type) {
  if (type == "int") return "an integer, e.g. 10";
  if (type == "double") return "a finite number, e.g. 0.01 or 1e-3";
  if (type == "bool") return "true or false";
  if (type == "Array(double)") return "{x, y, z} with finite numbers, e.g. {0, 0, -9.81}";
  if (type == "Array(int)") return "{i, j, ...} with integers";
  return type;
}

/// Checks that `value` reads as a `type` (only the types Teuchos reads laxly).
bool value_is_valid(const std::string& type, const std::string& value) {
  if (type != "int" && type != "double" && type != "bool" && type != "Array(double)" &&
      type != "Array(int)")
    return true;
  Teuchos::any like;
  if (type == "int") like = 0;
  if (type == "double") like = 0.0;
  if (type == "bool") like = false;
  if (type == "Array(double)") like = Teuchos::Array<double>();
  if (type == "Array(int)") like = Teuchos::Array<int>();
  if (type.rfind("Array", 0) == 0 && value.find('{') == std::string::npos) return false;
  try {
    parse_value(value, like);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

/// The `name` attribute of a <Parameter> or <ParameterList>.
std::string name_of(const Teuchos::XMLObject& x, const std::string& file, const std::string& path) {
  if (!x.hasAttribute("name"))
    throw InputError(file + ": a <" + x.getTag() + "> " +
                     (path.empty() ? "at the top level" : "in \"" + path + "\"") +
                     " has no name attribute");
  return x.getAttribute("name");
}

/// Refuses a name no --set, message or output can address: empty, holding '/' (the separator of
/// a parameter's path) or a control character (a newline in a name breaks one-line messages).
void check_name(const std::string& file, const std::string& path, const std::string& name) {
  const auto control = std::find_if(name.begin(), name.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  std::string what;
  if (name.empty())
    what = "an empty name";
  else if (name.find('/') != std::string::npos)
    what = "the name \"" + shorten(name) + "\" holds '/', which separates the levels of a path";
  else if (control != name.end())
    what = "the name \"" + shorten(name) + "\" holds a control character";
  if (what.empty()) return;
  fail(file, path.empty() ? "(top level)" : path,
       {"a parameter or list with " + what,
        "names of printable characters without '/', e.g. \"ball\" or \"ball on plate\""});
}

/// Scans a <ParameterList> element: names unique, values of int/double/bool/arrays valid.
void scan_list(const Teuchos::XMLObject& list, const std::string& path, const std::string& file) {
  std::set<std::string> seen;
  for (int i = 0; i < list.numChildren(); ++i) {
    const Teuchos::XMLObject& child = list.getChild(i);
    if (child.getTag() != "Parameter" && child.getTag() != "ParameterList") continue;
    const std::string name = name_of(child, file, path);
    const std::string p = path.empty() ? name : path + "/" + name;
    check_name(file, path, name);
    if (!seen.insert(name).second) fail(file, p, {"given twice", "each name once per list"});
    if (child.getTag() == "ParameterList") {
      scan_list(child, p, file);
      continue;
    }
    const std::string type = child.hasAttribute("type") ? child.getAttribute("type") : "";
    if (type.empty() || !child.hasAttribute("value"))
      fail(file, p,
           {"needs type and value attributes",
            "<Parameter name=\"" + shorten(name) + "\" type=\"double\" value=\"1\"/>"});
    const std::string& value = child.getAttribute("value");
    if (!value_is_valid(type, value))
      fail(file, p, {"value \"" + shorten(value) + "\" is not a valid " + type, value_hint(type)});
  }
}

}  // namespace

std::string read_xml_text(const std::string& file) {
  check_regular_file(file, "input");
  std::ifstream in(file, std::ios::binary);
  if (!in) cannot_read(file, std::strerror(errno));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) cannot_read(file, std::strerror(errno));
  return text;
}

Teuchos::RCP<Teuchos::ParameterList> read_xml(const std::string& file) {
  return parse_xml(file, read_xml_text(file));
}

Teuchos::RCP<Teuchos::ParameterList> parse_xml(const std::string& file, const std::string& raw) {
  const std::string text = utf8_text(raw, file);
  check_depth(file, text);
  try {
    Teuchos::StringInputSource source(text);
    const Teuchos::XMLObject xml = source.getObject();
    if (xml.getTag() != "ParameterList")
      cannot_read(file, "the top element is <" + shorten(xml.getTag()) + ">, not <ParameterList>");
    scan_list(xml, "", file);
    return Teuchos::getParametersFromXmlString(text);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    cannot_read(file, condense(e.what()));
  }
}

}  // namespace emc::input::detail
