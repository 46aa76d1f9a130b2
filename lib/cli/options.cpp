#include "cli/options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "generate/domains.h"
#include "io/format_registry.h"

namespace polydual::cli {

namespace {

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

using K = OptionKind;
constexpr double kNoRange = 0;

// Ranges come from the params structs where a stage owns the value.
const std::vector<OptionDef> kTable = {
    {"-o", K::Text, "OUT", kNoRange, kNoRange, "output file or directory (required)", nullptr,
     [](Settings& s, const std::string& v) { s.out = v; }},
    {"--format", K::Choice, poly_format_choices().c_str(), kNoRange, kNoRange, poly_format_help().c_str(), nullptr,
     [](Settings& s, const std::string& v) { s.format = v; }},
    {"--force", K::Flag, "", kNoRange, kNoRange,
     "write into an existing directory that is not an OpenFOAM case (convert) or an earlier demo's (demo), "
     "leaving its other files; replace a file whose extension is not the output's", nullptr,
     [](Settings& s, const std::string&) { s.write.foam.force = true; }},
    {"--vtu-encoding", K::Choice, "base64|raw|ascii", kNoRange, kNoRange,
     "VTU data arrays: base64 inline, raw appended binary (fastest to write and read), or ASCII text",
     [](const Settings& d) { return std::string(d.write.vtu.appended ? "raw" : d.write.vtu.binary ? "base64" : "ascii"); },
     [](Settings& s, const std::string& v) {
       s.write.vtu.binary = v != "ascii";
       s.write.vtu.appended = v == "raw";
     }},
    {"--zlib", K::Int, "LEVEL", 0, 9, "zlib compression of the VTU arrays (0: none; ParaView reads 1-9)",
     [](const Settings& d) { return std::to_string(d.write.vtu.zlib_level); },
     [](Settings& s, const std::string& v) { s.write.vtu.zlib_level = std::stoi(v); }},
    {"--feature-angle", K::Real, "DEG", ClassifyParams::kMinFeatureAngleDeg, ClassifyParams::kMaxFeatureAngleDeg,
     "dihedral angle (degrees) above which inferred model faces split",
     [](const Settings& d) { return num(d.params.classify.feature_angle_deg); },
     [](Settings& s, const std::string& v) { s.params.classify.feature_angle_deg = std::stod(v); }},
    {"--strong-angle", K::Real, "DEG", ClassifyParams::kMinFeatureAngleDeg, ClassifyParams::kMaxFeatureAngleDeg,
     "dihedral angle (degrees) above which a sharp edge is always a feature (below it, only in a feature line)",
     [](const Settings& d) { return num(d.params.classify.strong_angle_deg); },
     [](Settings& s, const std::string& v) { s.params.classify.strong_angle_deg = std::stod(v); }},
    {"--boundary", K::Choice, "keep|caps", kNoRange, kNoRange,
     "the dual's boundary: the primal's boundary triangulation, tiled by planar quads (each material's volume "
     "kept exactly), or the paper's caps joining the boundary triangles' centres",
     [](const Settings& d) { return std::string(boundary_mode_name(d.params.dual.boundary)); },
     [](Settings& s, const std::string& v) { s.params.set_boundary(parse_boundary_mode(v)); }},
    {"--no-cleanup", K::Flag, "", kNoRange, kNoRange, "skip the exact merge and the short-edge collapse", nullptr,
     [](Settings& s, const std::string&) { s.params.dual.cleanup = false; }},
    {"--collapse-tol", K::Real, "X", DualParams::kMinCollapseTolerance, DualParams::kMaxCollapseTolerance, "short-edge collapse length, relative to the mean primal edge",
     [](const Settings& d) { return num(d.params.dual.collapse_tolerance); },
     [](Settings& s, const std::string& v) { s.params.dual.collapse_tolerance = std::stod(v); }},
    {"--planarity", K::Real, "W", 0, OptimParams::kMaxPlanarity,
     "weight of a face-flatness term in the local optimiser's objective (0: the paper's objective)",
     [](const Settings& d) { return num(d.params.optim.planarity); },
     [](Settings& s, const std::string& v) { s.params.optim.planarity = std::stod(v); }},
    {"--no-split", K::Flag, "", kNoRange, kNoRange,
     "keep the dual without virtual cuts: slit cells at free edges and cells no placement makes valid stay",
     nullptr, [](Settings& s, const std::string&) { s.params.split.enabled = false; }},
    {"--split-rounds", K::Int, "N", 0, SplitParams::kMaxRounds,
     "most optimised rounds cutting the vertices of cells still invalid whole (one convex cell per tet; on a mixed mesh one barycentric corner per cell; on a surface mesh one corner polygon per cell), each untangling around the cut; then (tet meshes) a closure, bounded by the mesh, ends with every cell valid; 0: free-edge cuts only, no closure",
     [](const Settings& d) { return std::to_string(d.params.split.max_rounds); },
     [](Settings& s, const std::string& v) { s.params.split.max_rounds = std::stoi(v); }},
    {"--no-coarsen", K::Flag, "", kNoRange, kNoRange,
     "keep one cell per tet at every vertex the split cut whole, instead of merging those corners back while "
     "every cell stays valid",
     nullptr, [](Settings& s, const std::string&) { s.params.split.coarsen = false; }},
    {"--require-valid", K::Flag, "", kNoRange, kNoRange,
     "fail (exit 1, nothing written) if any cell is still invalid or the validation finds a defect (open cell, "
     "face error, missing model entity, volume mismatch), naming each cell",
     nullptr, [](Settings& s, const std::string&) { s.params.split.require_valid = true; }},
    {"--optimize", K::Choice, "auto|none|untangle|local|global", kNoRange, kNoRange,
     "untangle and smooth: the paper's local Newton scheme, a global Ceres L-BFGS solve, untangling only "
     "(certified valid, no smoothing), or none; auto: local on tet meshes, untangle on mixed meshes (smoothing "
     "would make their prism and hexahedron layers isotropic)",
     [](const Settings& d) { return std::string(method_name(d.params.optim.method)); },
     [](Settings& s, const std::string& v) { s.params.optim.method = parse_method(v); }},
    {"--no-optimize-tets", K::Flag, "", kNoRange, kNoRange,
     "skip the optimisation of the input tets' condition number before the dual (paper section 4; on by default: "
     "boundary vertices stay on their model faces and edges, with --boundary keep only where the model is flat, "
     "no tet is inverted)",
     nullptr, [](Settings& s, const std::string&) { s.params.tetopt.enabled = false; }},
    {"--optimize-tets", K::Flag, "", kNoRange, kNoRange,
     "optimise the input tets before the dual (the default; kept for scripts that ask for it)",
     nullptr, [](Settings& s, const std::string&) { s.params.tetopt.enabled = true; }},
    {"--tet-sweeps", K::Int, "N", 0, TetOptParams::kMaxSweeps, "sweeps of the tet optimisation, at most",
     [](const Settings& d) { return std::to_string(d.params.tetopt.max_sweeps); },
     [](Settings& s, const std::string& v) { s.params.tetopt.max_sweeps = std::stoi(v); }},
    {"--tet-flips", K::Choice, "on|off", kNoRange, kNoRange,
     "with the tet optimisation: Delaunay 2-3/3-2 flips after the moves (never on a model face or edge; "
     "the moves alone break the Delaunay property and invert dual edges)",
     [](const Settings& d) { return std::string(d.params.tetopt.flips.enabled ? "on" : "off"); },
     [](Settings& s, const std::string& v) { s.params.tetopt.flips.enabled = v == "on"; }},
    {"--interior-points", K::Choice, "on|off", kNoRange, kNoRange,
     "with the tet optimisation: insert interior vertices (Bowyer-Watson, exact predicates) into tets that "
     "span the solid, far larger than the mesh around them (TetGen -pY meshes of thick solids), before the moves; "
     "model faces, edges and vertices are kept",
     [](const Settings& d) { return std::string(d.params.tetopt.steiner.enabled ? "on" : "off"); },
     [](Settings& s, const std::string& v) { s.params.tetopt.steiner.enabled = v == "on"; }},
    {"--tet-flip-rounds", K::Int, "N", 1, TetFlipParams::kMaxRounds,
     "with the tet optimisation and flips: N rounds of the moves (to convergence) then the flips",
     [](const Settings& d) { return std::to_string(d.params.tetopt.flips.rounds); },
     [](Settings& s, const std::string& v) { s.params.tetopt.flips.rounds = std::stoi(v); }},
    {"--metric", K::Choice, "q1|q2", kNoRange, kNoRange, "corner set of the optimiser's objective and quality",
     [](const Settings& d) { return std::string(d.params.optim.metric == Metric::Q1 ? "q1" : "q2"); },
     [](Settings& s, const std::string& v) { s.params.optim.metric = parse_metric(v); }},
    {"--derivatives", K::Choice, "corrected|analytic|lagged|fd|exact", kNoRange, kNoRange,
     "local-scheme Newton derivatives: closed form with the cell and face centres lagged during a visit and "
     "their gradient added (corrected), closed form, lagged without the correction, finite differences (the "
     "paper) or ceres::Jet",
     [](const Settings& d) { return std::string(derivatives_name(d.params.optim.derivatives)); },
     [](Settings& s, const std::string& v) { s.params.optim.derivatives = parse_derivatives(v); }},
    {"--relaxation", K::Real, "OMEGA", 1, OptimParams::kMaxRelaxation,
     "over-relaxation of the local scheme's Newton step (1: the paper's damped Newton)",
     [](const Settings& d) { return num(d.params.optim.relaxation); },
     [](Settings& s, const std::string& v) { s.params.optim.relaxation = std::stod(v); }},
    {"--polish-sweeps", K::Int, "N", 0, OptimParams::kMaxIterLimit,
     "local scheme: sweeps over the points of the worst cells after the smoothing stops",
     [](const Settings& d) { return std::to_string(d.params.optim.polish_sweeps); },
     [](Settings& s, const std::string& v) { s.params.optim.polish_sweeps = std::stoi(v); }},
    {"--polish-share", K::Real, "S", 0, 1,
     "local scheme: the polish moves the points of the cells whose quality exceeds mean + S x (worst - mean) and of their neighbours",
     [](const Settings& d) { return num(d.params.optim.polish_share); },
     [](Settings& s, const std::string& v) { s.params.optim.polish_share = std::stod(v); }},
    {"--worst-rounds", K::Int, "N", 0, OptimParams::kMaxIterLimit,
     "local scheme, after the polish: rounds of min-max descent at the points of the worst cell (0: none)",
     [](const Settings& d) { return std::to_string(d.params.optim.worst_rounds); },
     [](Settings& s, const std::string& v) { s.params.optim.worst_rounds = std::stoi(v); }},
    {"--settle-move", K::Real, "X", 0, OptimParams::kMaxSettleMove,
     "local scheme: a point is revisited only while a point of its cells moved by more than X x the local "
     "length in the last two sweeps (0: while anything around it moved)",
     [](const Settings& d) { return num(d.params.optim.settle_move); },
     [](Settings& s, const std::string& v) { s.params.optim.settle_move = std::stod(v); }},
    {"--tol", K::Real, "X", 0, OptimParams::kMaxTol,
     "stop when a sweep lowers the objective by less than X relative",
     [](const Settings& d) {
       return d.params.optim.tol == OptimParams::kMethodTol ? std::string("2e-2 local, 1e-3 global")
                                                            : num(d.params.optim.tol);
     },
     [](Settings& s, const std::string& v) { s.params.optim.tol = std::stod(v); }},
    {"--max-iter", K::Int, "N", 0, OptimParams::kMaxIterLimit, "optimiser sweeps (local) or rounds (global), at most",
     [](const Settings& d) { return std::to_string(d.params.optim.max_iter); },
     [](Settings& s, const std::string& v) { s.params.optim.max_iter = std::stoi(v); }},
    {"--primal", K::Text, "MESH", kNoRange, kNoRange,
     "the tet mesh IN was built from: boundary points then slide on its model faces and edges", nullptr,
     [](Settings& s, const std::string& v) { s.primal = v; }},
    {"--tets", K::Int, "N", double(kMinTargetTets), double(kMaxTargetTets),
     "target number of tets per domain (layers: hexahedra and prisms; dfn: triangles; within ~30%)",
     [](const Settings& d) { return std::to_string(d.tets); },
     [](Settings& s, const std::string& v) { s.tets = std::stoll(v); }},
    {"--out", K::Text, "DIR", kNoRange, kNoRange, "output directory",
     [](const Settings& d) { return d.out_dir; }, [](Settings& s, const std::string& v) { s.out_dir = v; }},
    {"--domains", K::Text, "LIST", kNoRange, kNoRange, "comma-separated subset of cube,twomat,fichera,fracture,network,fins,layers,dfn",
     [](const Settings& d) { return d.domains; }, [](Settings& s, const std::string& v) { s.domains = v; }},
    {"--threads", K::Int, "N", 0, 1024, "worker threads (0: all cores); outputs do not depend on it",
     [](const Settings& d) { return std::to_string(d.threads); },
     [](Settings& s, const std::string& v) { s.threads = std::stoi(v); }},
    {"--json", K::Flag, "", kNoRange, kNoRange, "print one JSON summary object on stdout", nullptr,
     [](Settings& s, const std::string&) { s.json = true; }},
    {"--quiet", K::Flag, "", kNoRange, kNoRange, "no warnings or progress on stderr (an output's defects are still reported)", nullptr,
     [](Settings& s, const std::string&) { s.quiet = true; }},
};

bool looks_like_option(const std::string& s) {
  return s.size() > 1 && s[0] == '-' && !std::isdigit(static_cast<unsigned char>(s[1])) && s[1] != '.';
}

// Checks the value's type and range; throws UsageFailure naming the option.
void check_value(const OptionDef& o, const std::string& v) {
  const std::string name = o.name;
  if (o.kind == K::Choice) {
    const std::string choices = std::string("|") + o.value + "|";
    if (v.empty() || v.find('|') != std::string::npos || choices.find("|" + v + "|") == std::string::npos)
      throw UsageFailure("option " + name + ": '" + v + "' is not one of " + o.value);
    return;
  }
  if (o.kind != K::Int && o.kind != K::Real) return;
  char* end = nullptr;
  errno = 0;
  const double x = o.kind == K::Int ? double(std::strtoll(v.c_str(), &end, 10)) : std::strtod(v.c_str(), &end);
  if (v.empty() || *end || errno || !std::isfinite(x))
    throw UsageFailure("option " + name + ": '" + v + "' is not " + (o.kind == K::Int ? "an integer" : "a number"));
  if (x < o.lo || x > o.hi)
    throw UsageFailure("option " + name + ": " + v + " is outside [" + num(o.lo) + ", " + num(o.hi) + "]");
}

const OptionDef* find_in(const CommandSpec& spec, const std::string& name) {
  for (const std::string& use : spec.options)
    if (use.substr(0, use.find('=')) == name) return &option(name);
  return nullptr;
}

// Applies the "=VALUE" default overrides of a command's option list.
Settings command_defaults(const CommandSpec& spec, Settings d) {
  for (const std::string& use : spec.options)
    if (auto eq = use.find('='); eq != std::string::npos) option(use.substr(0, eq)).apply(d, use.substr(eq + 1));
  return d;
}

void check_positional(const CommandSpec& spec, const Settings& s) {
  if (s.help) return;
  if (int(s.positional.size()) < spec.min_positional)
    throw UsageFailure("missing argument for '" + spec.name + "': usage: polydual " + spec.synopsis);
  if (int(s.positional.size()) > spec.max_positional)
    throw UsageFailure("unexpected argument '" + s.positional[spec.max_positional] + "' for '" + spec.name + "'");
}

}  // namespace

const OptionDef& option(const std::string& name) {
  for (const OptionDef& o : kTable)
    if (name == o.name) return o;
  throw std::logic_error("option " + name + " is not declared in lib/cli/options.cpp");
}

Settings parse_command_line(const CommandSpec& spec, int argc, char** argv, Settings defaults) {
  Settings s = command_defaults(spec, std::move(defaults));
  std::set<std::string> given;  // a repeated option is refused: "last wins" hides typos
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") { s.help = true; continue; }
    if (!looks_like_option(arg)) { s.positional.push_back(arg); continue; }
    const auto eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const OptionDef* o = find_in(spec, name);
    if (!o) throw UsageFailure("unknown option '" + name + "' for '" + spec.name + "' (see polydual " + spec.name + " --help)");
    if (!given.insert(o->name).second) throw UsageFailure("option " + name + " is given twice; give it once");
    std::string value;
    if (o->kind == K::Flag) {
      if (eq != std::string::npos) throw UsageFailure("option " + name + " takes no value");
    } else if (eq != std::string::npos) {
      value = arg.substr(eq + 1);
    } else {
      if (i + 1 >= argc) throw UsageFailure("option " + name + " needs a value (" + o->value + ")");
      value = argv[++i];
    }
    check_value(*o, value);
    o->apply(s, value);
  }
  check_positional(spec, s);
  return s;
}

std::string help_text(const CommandSpec& spec, const Settings& defaults) {
  const Settings d = command_defaults(spec, defaults);
  std::ostringstream os;
  os << "usage: polydual " << spec.synopsis << "\n\n" << spec.description << "\n\noptions:\n";
  for (const std::string& use : spec.options) {
    const OptionDef& o = option(use.substr(0, use.find('=')));
    std::string lhs = std::string("  ") + o.name + (o.kind == K::Flag ? "" : std::string(" ") + o.value);
    os << lhs << std::string(lhs.size() < 28 ? 28 - lhs.size() : 1, ' ') << o.help;
    if (o.kind == K::Int || o.kind == K::Real) os << "; range [" << num(o.lo) << ", " << num(o.hi) << "]";
    if (o.default_text) os << " (default " << o.default_text(d) << ")";
    os << "\n";
  }
  os << "  -h, --help                  this help\n";
  return os.str();
}

}  // namespace polydual::cli
