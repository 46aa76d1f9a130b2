// Pieces shared by the msh 2.2 and msh 4.1 readers (not a public header).
#pragma once
#include <cstdint>
#include <string_view>

#include "io/text_cursor.h"
#include "mesh/tet_soup.h"

namespace polydual::io::msh {

// What the reader does with one Gmsh element type.
enum class Use { tet, triangle, line, point, ignore };

// Number of nodes of a Gmsh element type, or -1 when the type is unknown.
int node_count(std::int64_t type);
// Classifies the type, failing (at the cursor's place) for unknown types and
// for 3D types other than the linear tet.
Use element_use(const TextCursor& cur, std::int64_t type);

// Skips an unrecognised section up to and including "$End<name>".
void skip_section(TextCursor& cur, std::string_view name);
// Reads the token that must close section `name`.
void expect_end(TextCursor& cur, std::string_view name);

// Section loops after $MeshFormat (the cursor stands after $EndMeshFormat).
TetSoup read_msh2(TextCursor& cur, bool binary);
TetSoup read_msh4(TextCursor& cur, bool binary);

// Reads a binary value and rejects non-finite coordinates at their byte.
double binary_coordinate(TextCursor& cur, const char* what);

}  // namespace polydual::io::msh
