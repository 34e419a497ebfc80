// `prt report --glossy` (cli/glossy_report_cli.h).
#include "glossy_report_cli.h"

#include <cstdio>

#include "command_registry.h"
#include "material_option.h"
#include "progress_reporter.h"
#include "report/glossy_report.h"

namespace prt::cli {

void check_glossy_report_options(const GlossyReportRequest& r, const CLI::App& cmd) {
  if (r.stability || r.radiosity) throw UsageError("--glossy excludes --stability and --radiosity");
  if (r.scene.empty() || r.environment.empty())
    throw UsageError("--glossy needs a SCENE and an ENV");
  for (const char* option :
       {"--layout", "--haar-cubes", "--auto-tolerances", "--ground-truth-budget"})
    if (cmd.count(option) > 0)
      throw UsageError(std::string(option) + " does not apply to --glossy");
  parse_material_options(r.materials);
}

void run_glossy_report_command(const GlossyReportRequest& r) {
  prt::report::GlossyReportOptions o;
  o.scene_path = r.scene;
  o.environment_path = r.environment;
  o.output_dir = r.output;
  o.quick = r.quick;
  o.seed = r.seed;
  o.material_overrides = parse_material_options(r.materials);
  o.memory_limit = r.memory_limit;
  ProgressReporter progress(r.quiet);
  o.log = [&progress](const std::string& line) { progress.message(line); };
  o.progress = &progress;
  const prt::report::GlossyReportResult result = prt::report::run_glossy_report(o);
  for (const std::string& f : result.files_written) std::printf("wrote %s\n", f.c_str());
}

}  // namespace prt::cli
