// Editing an ASCII VTU's text in tests: the values of one DataArray
// rewritten, to make corrupted files from a good one.
#pragma once
#include <cstddef>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace polydual::testing {

// The VTU text `s` with the values of DataArray `name` (as text tokens, in
// file order) rewritten by `edit`.
inline std::string with_array(std::string s, const std::string& name,
                              const std::function<void(std::vector<std::string>&)>& edit) {
  const std::size_t tag = s.find("Name=\"" + name + "\"");
  const std::size_t begin = s.find('>', tag) + 1, end = s.find("</DataArray>", begin);
  std::istringstream in(s.substr(begin, end - begin));
  std::vector<std::string> values;
  for (std::string v; in >> v;) values.push_back(v);
  edit(values);
  std::string text = "\n";
  for (const std::string& v : values) text += " " + v;
  return s.replace(begin, end - begin, text + "\n");
}

}  // namespace polydual::testing
