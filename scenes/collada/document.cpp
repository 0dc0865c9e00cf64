#include "scenes/collada/document.h"

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>

#include "core/error.h"

namespace prism::collada {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// The first text child of `element` (where a number list lives), or a null node.
pugi::xml_node text_node(pugi::xml_node element) {
  for (pugi::xml_node child = element.first_child(); child; child = child.next_sibling()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) return child;
  }
  return {};
}

}  // namespace

std::string quote(std::string_view text) {
  constexpr size_t kMaxLength = 80;
  std::string out;
  for (char c : text.substr(0, kMaxLength)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (text.size() > kMaxLength) out += "...";
  return out;
}

std::string describe(pugi::xml_node node) {
  if (!node) return {};
  if (node.type() != pugi::node_element) return describe(node.parent());
  // The attributes that identify an element in these files, most telling first.
  static constexpr const char* kKeys[] = {"id",     "symbol",   "url",      "target",
                                          "source", "material", "semantic", "profile"};
  // Built by appending: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string.
  std::string out(1, '<');
  out += quote(node.name());
  int shown = 0;
  for (const char* key : kKeys) {
    const pugi::xml_attribute a = node.attribute(key);
    if (!a || shown == 2) continue;
    out += std::string(" ") + key + "=\"" + quote(a.value()) + "\"";
    ++shown;
  }
  return out + ">";
}

std::string_view trimmed_text(pugi::xml_node element) {
  std::string_view text = element.child_value();
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

pugi::xml_node find_extra_technique(pugi::xml_node parent, std::string_view profile) {
  for (pugi::xml_node extra : parent.children("extra")) {
    for (pugi::xml_node technique : extra.children("technique")) {
      if (profile == technique.attribute("profile").value()) return technique;
    }
  }
  return {};
}

pugi::xml_node first_element(pugi::xml_node node) {
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
    if (child.type() == pugi::node_element) return child;
  }
  return {};
}

Document::Document(const std::filesystem::path& path) : file_(path.string()) {
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::kInput, "cannot open the file for reading", {file_, 0, {}});
    text_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error(ErrorKind::kInput, "cannot read the file", {file_, 0, {}});
  }
  line_starts_.push_back(0);
  for (size_t i = 0; i < text_.size(); ++i) {
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
  }
  // In-place parsing keeps pugixml's offsets equal to byte offsets in the file, which is what
  // turns offset_debug() into line numbers.
  const pugi::xml_parse_result result =
      xml_.load_buffer_inplace(text_.data(), text_.size(), pugi::parse_default);
  if (!result) {
    int line = 0;
    if (result.offset >= 0) {
      const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(),
                                       static_cast<size_t>(result.offset));
      line = static_cast<int>(it - line_starts_.begin());
    }
    throw Error(ErrorKind::kInput, std::string("malformed XML: ") + result.description(),
                {file_, line, {}});
  }
  const pugi::xml_node top = xml_.document_element();
  if (!top) throw Error(ErrorKind::kInput, "the document has no root element", {file_, 1, {}});
  if (std::string_view(top.name()) != "COLLADA") {
    fail(top, "the root element must be <COLLADA>");
  }
  // Index every id with an explicit walk: recursion would let a deeply nested file overflow
  // the stack. The first element wins when an id repeats.
  pugi::xml_node node = top;
  while (node) {
    if (node.type() == pugi::node_element) {
      const pugi::xml_attribute id = node.attribute("id");
      if (id && *id.value()) ids_.try_emplace(std::string_view(id.value()), node);
    }
    if (node.first_child()) {
      node = node.first_child();
      continue;
    }
    while (node && node != top && !node.next_sibling()) node = node.parent();
    if (!node || node == top) break;
    node = node.next_sibling();
  }
}

int Document::line_of(pugi::xml_node node) const {
  if (!node) return 0;
  const ptrdiff_t offset = node.offset_debug();
  if (offset < 0) return 0;
  const auto it =
      std::upper_bound(line_starts_.begin(), line_starts_.end(), static_cast<size_t>(offset));
  return static_cast<int>(it - line_starts_.begin());
}

void Document::fail(pugi::xml_node node, const std::string& message) const {
  fail_at_line(node, line_of(node), message);
}

void Document::fail_at_line(pugi::xml_node node, int line, const std::string& message) const {
  throw Error(ErrorKind::kInput, message, {file_, line, describe(node)});
}

void Document::warn(pugi::xml_node node, const std::string& message) const {
  // The same one-line form as an error's what().
  std::string line =
      Error(ErrorKind::kInput, message, {file_, line_of(node), describe(node)}).what();
  // A node instanced several times (<instance_node>) is read, and would warn, each time.
  if (std::find(warnings_.begin(), warnings_.end(), line) == warnings_.end()) {
    warnings_.push_back(std::move(line));
  }
}

pugi::xml_node Document::find_id(std::string_view id) const {
  const auto it = ids_.find(id);
  return it == ids_.end() ? pugi::xml_node() : it->second;
}

pugi::xml_node Document::resolve(pugi::xml_node referrer, const char* attribute,
                                 std::string_view expected) const {
  const pugi::xml_attribute a = referrer.attribute(attribute);
  if (!a) fail(referrer, std::string("missing attribute '") + attribute + "'");
  const std::string_view value = a.value();
  if (value.size() < 2 || value.front() != '#') {
    fail(referrer, std::string(attribute) + "=\"" + quote(value) +
                       "\" is not a local reference of the form #id (external documents are "
                       "not supported)");
  }
  const std::string_view id = value.substr(1);
  const pugi::xml_node target = find_id(id);
  if (!target) fail(referrer, "dangling reference: no element has id '" + quote(id) + "'");
  if (expected != target.name()) {
    fail(referrer, "reference '#" + quote(id) + "' names a <" + quote(target.name()) +
                       ">, expected <" + std::string(expected) + ">");
  }
  return target;
}

pugi::xml_node Document::require_child(pugi::xml_node parent, const char* name) const {
  const pugi::xml_node child = parent.child(name);
  if (!child) fail(parent, std::string("missing <") + name + ">");
  return child;
}

template <typename T>
std::vector<T> Document::parse_numbers(pugi::xml_node element, bool integers) const {
  std::vector<T> out;
  const pugi::xml_node text = text_node(element);
  if (!text) return out;
  const char* const begin = text.value();
  const char* const end = begin + std::char_traits<char>::length(begin);
  const auto token_error = [&](const char* token, const char* token_end, const char* what) {
    const int line = line_of(text) + static_cast<int>(std::count(begin, token, '\n'));
    fail_at_line(element, line,
                 "'" + quote(std::string_view(token, token_end - token)) + "' " + what);
  };
  const char* p = begin;
  while (true) {
    while (p < end && is_space(*p)) ++p;
    if (p == end) break;
    const char* token_end = p;
    while (token_end < end && !is_space(*token_end)) ++token_end;
    if (integers) {
      uint64_t value = 0;
      const auto [ptr, ec] = std::from_chars(p, token_end, value);
      if (ec != std::errc() || ptr != token_end || value > UINT32_MAX) {
        token_error(p, token_end, "is not an integer index in [0, 2^32)");
      }
      out.push_back(static_cast<T>(value));
    } else {
      // from_chars rejects a leading '+', which C's strtod (and so the homework) accepts.
      const char* start = (*p == '+' && token_end - p > 1) ? p + 1 : p;
      double value = 0.0;
      const auto [ptr, ec] = std::from_chars(start, token_end, value);
      if (ec == std::errc::result_out_of_range) token_error(p, token_end, "is out of range");
      if (ec != std::errc() || ptr != token_end) token_error(p, token_end, "is not a number");
      if (!std::isfinite(value)) token_error(p, token_end, "is not a finite number");
      if (std::is_same_v<T, float> && std::abs(value) > FLT_MAX) {
        token_error(p, token_end, "is too large for single precision");
      }
      out.push_back(static_cast<T>(value));
    }
    p = token_end;
  }
  return out;
}

std::vector<float> Document::floats(pugi::xml_node element) const {
  return parse_numbers<float>(element, false);
}

std::vector<double> Document::doubles(pugi::xml_node element) const {
  return parse_numbers<double>(element, false);
}

std::vector<uint32_t> Document::indices(pugi::xml_node element) const {
  return parse_numbers<uint32_t>(element, true);
}

double Document::scalar(pugi::xml_node element) const {
  // Parsed as floats so a value that would overflow where it is stored (a float) is an error.
  const std::vector<float> v = floats(element);
  if (v.size() != 1) {
    fail(element, "expected one number, found " + std::to_string(v.size()));
  }
  return v[0];
}

Rgb Document::color(pugi::xml_node element) const {
  std::vector<float> v = floats(element);
  // The homework streams the numbers into r, g, b of a zero colour: one or two numbers leave
  // the rest 0, more than three are never read (an empty colour crashes it).
  if (v.empty()) fail(element, "expected an RGB or RGBA colour (3 or 4 numbers), found 0");
  if (v.size() < 3) {
    warn(element, std::to_string(v.size()) + (v.size() == 1 ? " number" : " numbers") +
                      ", not 3; the missing ones are read as 0, as the CS184 homework does");
    v.resize(3, 0.0f);
  } else if (v.size() > 4) {
    warn(element,
         std::to_string(v.size()) +
             " numbers, not 3 or 4; only the first 3 are read, as the CS184 homework does");
  }
  if (v[0] < 0.0f || v[1] < 0.0f || v[2] < 0.0f) fail(element, "colour components must be >= 0");
  return Rgb(v[0], v[1], v[2]);
}

int Document::token_line(pugi::xml_node element, size_t index) const {
  const pugi::xml_node text = text_node(element);
  if (!text) return line_of(element);
  const char* p = text.value();
  int line = line_of(text);
  size_t seen = 0;
  while (*p) {
    while (*p && is_space(*p)) line += (*p++ == '\n');
    if (!*p) break;
    if (seen++ == index) return line;
    while (*p && !is_space(*p)) ++p;
  }
  return line_of(element);
}

uint64_t Document::uint_attribute(pugi::xml_node element, const char* name,
                                  uint64_t fallback) const {
  const pugi::xml_attribute a = element.attribute(name);
  if (!a) return fallback;
  std::string_view text = a.value();
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) {
    fail(element,
         std::string(name) + "=\"" + quote(a.value()) + "\" is not a non-negative integer");
  }
  return value;
}

}  // namespace prism::collada
