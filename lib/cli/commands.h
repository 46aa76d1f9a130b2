#pragma once
#include "cli/args.h"

namespace polydual::cli {

extern const CommandSpec kGenerate, kInfo, kConvert, kCheck, kDemo, kOptimize;
int cmd_generate(const Args& a);
int cmd_info(const Args& a);
int cmd_convert(const Args& a);
int cmd_check(const Args& a);
int cmd_demo(const Args& a);
int cmd_optimize(const Args& a);

}  // namespace polydual::cli
