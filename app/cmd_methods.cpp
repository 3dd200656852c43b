// `atssim methods`: the simulation methods of the registry, their options
// and the solid models they simulate (scripts iterate it with --json).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "solver/method_registry.hpp"

namespace atssim::app {

Action add_methods_command(CLI::App& cli) {
  CLI::App* cmd = cli.add_subcommand("methods", "List the simulation methods, their options and solid models");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "Print JSON");
  return [json]() {
    const auto all = solver::methods();
    if (*json) fmt::print("[\n");
    for (std::size_t i = 0; i < all.size(); ++i) {
      const solver::MethodDescription& m = *all[i];
      std::string solids, options;
      for (scene::SolidModel s : m.solid_models) {
        const std::string_view name = scene::to_string(s);
        solids += *json ? fmt::format("{}\"{}\"", solids.empty() ? "" : ", ", name)
                        : fmt::format("{}{}", solids.empty() ? "" : ", ", name);
      }
      for (const solver::MethodOption& o : m.options) {
        const std::string value = o.choices.empty() ? o.default_text() : fmt::format("\"{}\"", o.default_text());
        options += *json ? fmt::format("{}{{\"key\": \"{}\", \"default\": {}, \"min\": {}, \"max\": {}}}",
                                       options.empty() ? "" : ", ", o.key, value, o.min, o.max)
                         : fmt::format("{}solver.{} = {} ({})", options.empty() ? "" : "; ", o.key, o.default_text(),
                                       o.meaning);
      }
      std::string kinds;
      for (const plan::TaskKind& k : m.kinds) kinds += fmt::format("{}\"{}\"", kinds.empty() ? "" : ", ", k.name());
      if (*json) {
        fmt::print(
            "  {{\"name\": \"{}\", \"iterations\": \"{}\", \"summary\": \"{}\", \"program\": \"{}\", "
            "\"kinds\": [{}], \"implicit\": {}, \"descent\": {}, \"colliders\": {}, \"solids\": [{}], "
            "\"options\": [{}]}}{}\n",
            m.name, m.gauss_seidel ? "gauss_seidel" : "jacobi", m.summary, m.program, kinds, m.implicit, m.descent,
            m.colliders, solids, options, i + 1 < all.size() ? "," : "");
      } else {
        fmt::print("{:<6} {} ({}; solids: {}){}\n", m.name, m.summary, m.gauss_seidel ? "Gauss-Seidel" : "Jacobi",
                   solids.empty() ? "none" : solids, options.empty() ? "" : "\n       options: " + options);
      }
    }
    if (*json) fmt::print("]\n");
    return 0;
  };
}

}  // namespace atssim::app
