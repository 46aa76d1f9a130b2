// The polydual command (lib/cli): parses options, composes stages, prints.
#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  if (argc < 2) { std::fprintf(stderr, "usage: polydual COMMAND ...\n"); return 2; }
  return 0;
}
