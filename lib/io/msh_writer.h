// Gmsh msh 4.1 ASCII writer. $Entities is synthesised from the tags so that
// reading the file back gives the same classification: one volume entity per
// distinct region (entity tags 1.., physical tag = region), one surface / curve /
// point entity per distinct triangle / edge / corner tag (entity tag = that
// tag, which is what the reader returns). Gmsh itself wants positive entity
// tags, so soups with zero or negative model tags only round-trip through us.
#pragma once
#include <string>

#include "mesh/tet_soup.h"

namespace polydual {

void write_msh(const TetSoup& soup, const std::string& path);

}  // namespace polydual
