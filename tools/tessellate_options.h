// Options the subdivision commands (tessellate, render, accuracy) share: scheme, factors, partitioning.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "subd_model.h"
#include "subd_patches.h"
#include "subd_shaders.h"
#include "tessellator.h"

namespace tessera::cli {

void add_scheme_options(CLI::App& cmd, std::string& scheme, float& factor, float& vary, std::string& factors_file,
                        std::string& partitioning, int& threads);
Scheme scheme_option(const std::string& name);
ts::Partitioning partitioning_option(const std::string& name);
// --factor, --vary-factors and --factors-per-edge FILE (lines "v0 v1 factor", cage vertex indices from
// 0; edges not listed take --factor).
SubdFactors factors_option(float factor, float vary, const std::string& file);
// load_subd_model with its CageError turned into the CLI's InputError (one line, exit 1).
SubdModel load_model(const std::string& path, Scheme scheme);

}  // namespace tessera::cli
