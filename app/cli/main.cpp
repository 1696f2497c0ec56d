// `tactile`: the command line for every headless job (run.cpp). Core only, no ImGui.
#include "commands.h"

int main(int argc, char** argv) { return tactile::cli::run(argc, argv); }
