#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <pugixml.hpp>

#include "core/math.h"

namespace prism::collada {

/// A parsed COLLADA file: the XML tree, an index of every `id`, and the byte-offset -> line
/// table that locates errors. Every failure throws Error(kInput) carrying the file, the 1-based
/// line and a short description of the element, so the user sees one line such as
/// `scene.dae:42: <float_array id="pos">: count="9" but the element holds 6 numbers`.
/// Not thread-safe; the nodes it hands out live as long as the Document.
class Document {
 public:
  /// Reads and parses `path`. Throws Error(kInput) when the file cannot be read or is not
  /// well-formed XML (pugixml's description and the line of the fault).
  explicit Document(const std::filesystem::path& path);

  /// The root element (<COLLADA>; checked by the constructor).
  pugi::xml_node root() const { return xml_.document_element(); }
  const std::string& file() const { return file_; }

  /// 1-based line where `node` starts, or 0 when pugixml cannot tell.
  int line_of(pugi::xml_node node) const;

  /// Throws Error(kInput) located at `node` (line and description) with `message`.
  [[noreturn]] void fail(pugi::xml_node node, const std::string& message) const;
  /// As fail(node, message) but at an explicit line (e.g. of one token inside a long list).
  [[noreturn]] void fail_at_line(pugi::xml_node node, int line, const std::string& message) const;

  /// Records a tolerated defect located at `node`, formatted like an error's one line:
  /// `file:line: <element>: message`. The document is const to its readers; the warnings are
  /// the only state they add to it.
  void warn(pugi::xml_node node, const std::string& message) const;
  /// Every warning recorded so far, in order.
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The element with id `id`, or a null node.
  pugi::xml_node find_id(std::string_view id) const;

  /// Follows the "#id" reference in attribute `attribute` of `referrer` and checks that it names
  /// an element called `expected`. Throws naming the id when the attribute is missing, is not a
  /// local "#id" reference, dangles, or names the wrong kind of element.
  pugi::xml_node resolve(pugi::xml_node referrer, const char* attribute,
                         std::string_view expected) const;

  /// First child element `name` of `parent`; throws naming `parent` and `name` when absent.
  pugi::xml_node require_child(pugi::xml_node parent, const char* name) const;

  /// Every number in the text of `element`, each finite and within float range. Throws naming
  /// the element, the offending token and its line otherwise. Memory is proportional to the
  /// text actually present, never to a count attribute.
  std::vector<float> floats(pugi::xml_node element) const;
  /// As floats() but in double precision (transforms).
  std::vector<double> doubles(pugi::xml_node element) const;
  /// Every non-negative integer below 2^32 in the text of `element` (<p>, <vcount>).
  std::vector<uint32_t> indices(pugi::xml_node element) const;
  /// Exactly one number in `element`, finite and within float range.
  double scalar(pugi::xml_node element) const;
  /// An RGB colour: three numbers, or four with the alpha ignored; each must be >= 0. Read as
  /// the CS184 homework reads it: with one or two numbers the missing ones are 0, with more
  /// than four only the first three count; both warn (warn()). None at all throws.
  Rgb color(pugi::xml_node element) const;
  /// The line of the `index`-th whitespace-separated token of `element`'s text (for errors in
  /// long lists); the element's own line when the token cannot be found.
  int token_line(pugi::xml_node element, size_t index) const;

  /// A non-negative integer attribute; `fallback` when absent. Throws when present but not an
  /// integer.
  uint64_t uint_attribute(pugi::xml_node element, const char* name, uint64_t fallback) const;

 private:
  template <typename T>
  std::vector<T> parse_numbers(pugi::xml_node element, bool integers) const;

  std::string file_;
  std::string text_;                 // the file's bytes, for line numbers
  std::vector<size_t> line_starts_;  // byte offset at which each line starts
  pugi::xml_document xml_;
  std::unordered_map<std::string_view, pugi::xml_node> ids_;
  mutable std::vector<std::string> warnings_;
};

/// A short, single-line description of an element for error messages, such as
/// `<polylist material="white">` or `<float_array id="pos">` (attributes that identify it).
std::string describe(pugi::xml_node node);

/// `text` made safe for a one-line message: control characters replaced, long text cut.
std::string quote(std::string_view text);

/// The text of `element` with leading and trailing whitespace removed.
std::string_view trimmed_text(pugi::xml_node element);

/// The child element named `name` of `parent` whose `profile` attribute is `profile` (e.g. the
/// <technique profile="CGL"> inside an <extra>), searching every <extra> child of `parent`.
pugi::xml_node find_extra_technique(pugi::xml_node parent, std::string_view profile);

/// First child element of `node` (skipping text and comments), or a null node.
pugi::xml_node first_element(pugi::xml_node node);

}  // namespace prism::collada
