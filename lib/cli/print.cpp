#include "cli/print.h"

#include <cstdio>
#include <iostream>

namespace polydual::cli {

std::string json_text(const Json& j) { return j.dump(0); }

void print_json(const Json& j) { std::cout << j.dump() << "\n"; }

void print_convert_summary(const Json& j) {
  auto val = [&](const char* k) { return j.find(k) ? j.find(k)->dump(0) : std::string("?"); };
  const Json* out = j.find("output");
  std::printf("%s -> %s\n", val("input").c_str(), out && out->find("path") ? out->find("path")->dump(0).c_str() : "?");
  std::printf("  tets %s -> cells %s, faces %s, points %s\n", val("tets").c_str(), val("cells").c_str(),
              val("faces").c_str(), val("points").c_str());
  std::printf("  invalid cells (exact star test): before %s, after %s; closed cells %s; slit cells %s\n",
              val("invalid_before").c_str(), val("invalid_after").c_str(), val("closed_cells").c_str(),
              val("slit_cells").c_str());
  std::printf("  seconds %s\n", val("seconds").c_str());
}

}  // namespace polydual::cli
