// meshnbv: command line front end of the MeshNBV core (cli_main.cpp).
#include "commands.h"

int main(int argc, char** argv) { return meshnbv::cli::run_main(argc, argv, "meshnbv"); }
