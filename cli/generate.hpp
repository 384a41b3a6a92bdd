// `pge generate`: write a scene of a deterministic family.
#pragma once

#include "pge/families.hpp"

#include <string>

namespace pge::cli {

struct GenerateOptions {
  std::string family = "gas";
  GasParams gas;
  std::string out;  // "" or "-": stdout
};

int generate_command(const GenerateOptions& options);

}  // namespace pge::cli
