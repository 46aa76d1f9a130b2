// VTK XML element scanning and the <VTKFile>/<Piece>/<AppendedData> checks
// (lib/io/vtk_xml.h). DataArray decoding is in vtk_xml_arrays.cpp.
#include "io/vtk_xml.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/text_cursor.h"

namespace polydual::io::vtkxml {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

namespace {

// Fails at the first NUL byte of bytes[from, end) unless raw appended data
// began before it; true once it has (no later byte needs checking).
bool check_text(const std::string& source, std::string_view bytes, std::size_t from) {
  const std::size_t nul = bytes.find('\0', from);
  if (nul == std::string_view::npos) return false;
  if (bytes.substr(0, nul).find("<AppendedData") != std::string_view::npos) return true;
  fail_nul_byte(source, bytes, nul);
}

// The first bytes, before the rest is read: blanks (after a byte-order mark),
// then declarations and comments, then <VTKFile. Only what `head` holds is
// judged (a prolog longer than the head is left to the full scan).
void check_head(const std::string& source, std::string_view head) {
  auto not_vtk = [&](std::size_t at, const std::string& why) {
    throw InputError(source, "line " + std::to_string(line_of(head, at)), "not a VTK XML file (" + why + ")");
  };
  std::size_t p = head.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
  while ((p = head.find_first_not_of(" \t\r\n", p)) != std::string_view::npos) {
    if (head[p] != '<') not_vtk(p, "it starts with '" + quoted(head.substr(p, 16)) + "', not with a tag");
    if (head.substr(p, 2) != "<?" && head.substr(p, 2) != "<!") break;
    const std::string_view close = head.substr(p, 2) == "<?" ? "?>" : head.substr(p, 4) == "<!--" ? "-->" : ">";
    const std::size_t e = head.find(close, p);
    if (e == std::string_view::npos) return;
    p = e + close.size();
  }
  if (p != std::string_view::npos && head.size() - p >= 8 && head.substr(p, 8) != "<VTKFile")
    not_vtk(p, "its first element is '" + quoted(head.substr(p, 16)) + "', not <VTKFile>");
}

// The last non-blank byte of the file must close a tag.
void check_tail(const InputFile& file) {
  const std::string tail = file.tail(4096);
  const std::size_t last = tail.find_last_not_of(" \t\r\n");
  if (last == std::string::npos || tail[last] == '>') return;  // all blank: nothing to judge by
  const std::uint64_t at = file.size() - tail.size() + last;
  throw InputError(file.path(), "byte " + std::to_string(at),
                   tail[last] == '\0' ? "the file ends in NUL bytes, not in </VTKFile> (zero-filled or cut short?)"
                                      : "the file does not end in </VTKFile> (cut short?)");
}

}  // namespace

std::string_view load_vtk_xml(InputFile& file) {
  std::string_view b = file.load_to(1);
  bool binary = check_text(file.path(), b, 0);
  check_head(file.path(), b);
  check_tail(file);
  while (b.size() < file.size()) {
    const std::size_t had = b.size();
    b = file.load_to(2 * had);
    if (!binary) binary = check_text(file.path(), b, had);
  }
  return file.load_to(file.size() + 1);  // and not longer than at open
}

VtkXml::VtkXml(std::string_view bytes, std::string source, std::string_view grid_type)
    : bytes_(bytes), source_(std::move(source)) {
  scan();
  check_root();
  const Element& root = elements_.front();
  if (root.attr("type").value_or("") != grid_type)
    fail(root.begin, "VTK file of type '" + quoted(root.attr("type").value_or("")) + "' (expected " +
                         std::string(grid_type) + ")");
}

std::size_t VtkXml::line_at(std::size_t pos) const {
  pos = std::min(pos, bytes_.size());
  return 1 + static_cast<std::size_t>(std::count(bytes_.begin(), bytes_.begin() + static_cast<long>(pos), '\n'));
}
void VtkXml::fail(std::size_t pos, const std::string& what) const {
  throw InputError(source_, "line " + std::to_string(line_at(pos)), what);
}
void VtkXml::fail_byte(std::size_t pos, const std::string& what) const {
  throw InputError(source_, "byte " + std::to_string(pos), what);
}
void VtkXml::fail_at(const std::string& place, const std::string& what) const {
  throw InputError(source_, place, what);
}

// The element tree: every start tag becomes an Element, end tags must match.
void VtkXml::scan() {
  check_text(source_, bytes_, 0);  // load_vtk_xml checked a file as it loaded; buffers arrive unchecked
  std::vector<int> stack;
  std::size_t pos = 0;
  while (true) {
    const std::size_t lt = bytes_.find('<', pos);
    if (lt == std::string_view::npos) break;
    auto skip_to = [&](std::string_view close) {
      const std::size_t e = bytes_.find(close, lt);
      if (e == std::string_view::npos) fail(lt, "unterminated '" + quoted(bytes_.substr(lt, 4)) + "'");
      return e + close.size();
    };
    if (bytes_.substr(lt, 4) == "<!--") { pos = skip_to("-->"); continue; }
    if (bytes_.substr(lt, 2) == "<?") { pos = skip_to("?>"); continue; }
    if (bytes_.substr(lt, 2) == "<!") { pos = skip_to(">"); continue; }
    pos = scan_tag(lt, stack);
  }
  if (elements_.empty() && bytes_.find_first_not_of(" \t\r\n") == std::string_view::npos)
    fail_at("", "the file is empty");
  if (!stack.empty()) fail(bytes_.size(), "file ends inside <" + quoted(elements_[stack.back()].name) + ">");
  if (elements_.empty() || elements_.front().name != "VTKFile") fail(0, "not a VTK XML file (no <VTKFile>)");
}

// One start, end or empty tag at `lt`; returns the offset after it (after the
// appended data for <AppendedData>).
std::size_t VtkXml::scan_tag(std::size_t lt, std::vector<int>& stack) {
  std::size_t p = lt + 1;
  const bool closing = p < bytes_.size() && bytes_[p] == '/';
  if (closing) ++p;
  const std::size_t name_begin = p;
  while (p < bytes_.size() && !is_space(bytes_[p]) && bytes_[p] != '>' && bytes_[p] != '/') ++p;
  Element e;
  e.name = bytes_.substr(name_begin, p - name_begin);
  e.begin = lt;
  if (e.name.empty()) fail(lt, "malformed XML tag");
  bool empty = false;
  while (true) {
    while (p < bytes_.size() && is_space(bytes_[p])) ++p;
    if (p >= bytes_.size()) fail(lt, "XML tag <" + quoted(e.name) + "> is not closed");
    if (bytes_[p] == '>') { ++p; break; }
    if (bytes_[p] == '/' && p + 1 < bytes_.size() && bytes_[p + 1] == '>') { empty = true; p += 2; break; }
    if (closing) fail(lt, "malformed end tag </" + quoted(e.name) + ">");
    const std::size_t key_begin = p;
    while (p < bytes_.size() && bytes_[p] != '=' && !is_space(bytes_[p]) && bytes_[p] != '>') ++p;
    const std::string_view key = bytes_.substr(key_begin, p - key_begin);
    while (p < bytes_.size() && is_space(bytes_[p])) ++p;
    if (p >= bytes_.size() || bytes_[p] != '=') fail(p, "expected '=' after attribute '" + quoted(key) + "'");
    ++p;
    while (p < bytes_.size() && is_space(bytes_[p])) ++p;
    if (p >= bytes_.size() || (bytes_[p] != '"' && bytes_[p] != '\''))
      fail(p, "expected a quoted value for attribute '" + quoted(key) + "'");
    const char quote = bytes_[p++];
    const std::size_t close = bytes_.find(quote, p);
    if (close == std::string_view::npos) fail(p, "unterminated attribute value");
    e.attrs.emplace_back(key, bytes_.substr(p, close - p));
    p = close + 1;
  }
  if (closing) {
    if (stack.empty() || elements_[stack.back()].name != e.name) fail(lt, "unexpected </" + quoted(e.name) + ">");
    stack.pop_back();
    return p;
  }
  if (elements_.empty() != stack.empty()) fail(lt, "more than one root element");
  e.parent = stack.empty() ? -1 : stack.back();
  if (!empty) {
    const std::size_t next = std::min(bytes_.find('<', p), bytes_.size());
    e.text = bytes_.substr(p, next - p);
    e.text_pos = p;
    stack.push_back(static_cast<int>(elements_.size()));
  }
  elements_.push_back(std::move(e));
  if (elements_.back().name == "AppendedData" && !empty) {
    scan_appended(elements_.back(), p);
    return appended_->second;  // at its </AppendedData>
  }
  return p;
}

// <AppendedData encoding="raw|base64">, whitespace, '_', data, </AppendedData>.
// Raw data may hold any byte, '<' included: the section ends at the last
// </AppendedData> of the file.
void VtkXml::scan_appended(const Element& e, std::size_t after_tag) {
  if (appended_) fail(e.begin, "more than one <AppendedData>");
  const std::string_view encoding = e.attr("encoding").value_or("");
  if (encoding != "raw" && encoding != "base64")
    fail(e.begin, "AppendedData encoding '" + quoted(encoding) + "' not supported (raw or base64)");
  appended_base64_ = encoding == "base64";
  std::size_t p = after_tag;
  while (p < bytes_.size() && is_space(bytes_[p])) ++p;
  if (p >= bytes_.size() || bytes_[p] != '_') fail(e.begin, "AppendedData does not start with '_'");
  const std::size_t end = bytes_.rfind("</AppendedData>");
  if (end == std::string_view::npos || end <= p) fail(e.begin, "AppendedData is not closed by </AppendedData>");
  appended_.emplace(p + 1, end);
  elements_.back().text = {};
}

void VtkXml::check_root() {
  const Element& root = elements_.front();
  if (root.attr("byte_order").value_or("LittleEndian") != "LittleEndian")
    fail(root.begin, "big-endian VTU not supported");
  const std::string_view h = root.attr("header_type").value_or("UInt32");
  if (h != "UInt32" && h != "UInt64") fail(root.begin, "header_type '" + quoted(h) + "' not supported");
  header64_ = h == "UInt64";
  if (const auto c = root.attr("compressor")) {
    if (*c != "vtkZLibDataCompressor")
      fail(root.begin, "compressor '" + quoted(*c) + "' not supported (only vtkZLibDataCompressor)");
    zlib_ = true;
  }
}

const Element& VtkXml::piece() const {
  const Element* found = nullptr;
  for (const Element& e : elements_) {
    if (e.name != "Piece") continue;
    if (found) fail(e.begin, "more than one Piece not supported");
    found = &e;
  }
  if (!found) fail(0, "no <Piece> in the " + std::string(elements_.front().attr("type").value_or("")));
  return *found;
}

const Element* VtkXml::find_array(std::string_view section, std::string_view name) const {
  for (const Element& e : elements_)
    if (e.name == "DataArray" && parent_name(e) == section && (name.empty() || e.attr("Name") == name)) return &e;
  return nullptr;
}

std::int64_t VtkXml::count_attr(const Element& e, std::string_view key) const {
  const auto v = e.attr(key);
  if (!v) {
    std::string what = "<";  // built by append: GCC 12 warns falsely (-Wrestrict) on a + chain here
    what.append(e.name).append("> has no ").append(key);
    fail(e.begin, what);
  }
  TextCursor cur(*v, source_);
  cur.set_first_line(line_at(e.begin));
  const std::int64_t n = cur.integer_in(std::string(key).c_str(), 0, static_cast<std::int64_t>(bytes_.size()));
  if (!cur.at_end()) fail(e.begin, std::string(key) + " is not an integer");
  return n;
}

}  // namespace polydual::io::vtkxml
