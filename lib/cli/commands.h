// The subcommands: each turns Settings (parsed from the option table) into
// library calls and prints the result. Nothing else lives in lib/cli.
#pragma once
#include "cli/options.h"

namespace polydual::cli {

extern const CommandSpec kGenerate, kInfo, kConvert, kCheck, kDemo, kOptimize;
int cmd_generate(const Settings& s);
int cmd_info(const Settings& s);
int cmd_convert(const Settings& s);
int cmd_check(const Settings& s);
int cmd_demo(const Settings& s);
int cmd_optimize(const Settings& s);

}  // namespace polydual::cli
