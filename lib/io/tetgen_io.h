// TetGen .node / .ele / .face (optional), read and written together by
// basename. .node: "n 3 nattr bmark", then "idx x y z [attrs] [marker]"; the
// first index (0 or 1) fixes the numbering base for all three files. .ele:
// "n 4 nattr", then "idx a b c d [attrs]"; the first attribute is the region
// (TetGen's -A region attribute; no attribute -> region 1). .face: "n bmark",
// then "idx a b c [marker]" -> tagged triangles with the marker as tag (marker
// 0 faces are kept with tag 0). Edges and corners are not part of the format.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "mesh/tet_soup.h"

namespace polydual {

// Memory API: the contents of the files; `basename` names them in errors
// (basename + ".node", ...). `face` is std::nullopt when there is no .face.
TetSoup read_tetgen(std::string_view node, std::string_view ele, std::optional<std::string_view> face,
                    const std::string& basename);
// `path` is the .node or .ele file (or the basename); the .face file is read
// when it exists.
TetSoup read_tetgen_files(const std::string& path);
// Writes basename.node, basename.ele (region attribute) and, when the soup has
// triangles, basename.face (1-based numbering, as TetGen writes by default).
void write_tetgen(const TetSoup& soup, const std::string& path);

// The basename of a TetGen path: strips .node, .ele or .face.
std::string tetgen_basename(const std::string& path);

}  // namespace polydual
