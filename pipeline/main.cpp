// slowlight: slow-motion videos of light, rendered by transient progressive photon mapping.
#include "pipeline/cli.h"

int main(int argc, char** argv) { return sl::run_cli(argc, argv); }
