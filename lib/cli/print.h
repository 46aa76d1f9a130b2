// Human-readable lines for the summaries the library returns, and the
// warnings of a read (stderr unless --quiet).
#pragma once
#include "core/json.h"
#include "mesh/tet_soup.h"

namespace polydual::cli {

void print_convert_summary(const Json& summary);
void print_json(const Json& j);  // one object on stdout
std::string json_text(const Json& j);  // compact one-line dump of a value

}  // namespace polydual::cli
