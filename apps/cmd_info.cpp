// `weft info`: versions, backends and devices.
#include "apps/cli.hpp"
#include "core/kokkos_compat.hpp"
#include "weft_version.hpp"

#include <iostream>

namespace weft::cli {

namespace {

void add_info(CLI::App& app, const GlobalOptions& g, Action& run) {
  auto* cmd = app.add_subcommand("info", "print versions, enabled backends and devices");
  cmd->callback([&g, &run] {
    run = [&g] {
      const Backend b = resolve_backend(g);
      Runtime rt(g.threads);
      std::cout << "weft " << WEFT_VERSION << "\n";
      std::cout << "kokkos " << compat::kokkos_version_string() << "\n";
      std::cout << "backends:";
      for (Backend c : compiled_backends()) std::cout << " " << backend_name(c);
      std::cout << "\nselected backend: " << backend_name(b) << "\n";
      for (const auto& line : describe_devices()) std::cout << line << "\n";
      return 0;
    };
  });
}

const Register reg("info", add_info);

}  // namespace
}  // namespace weft::cli
