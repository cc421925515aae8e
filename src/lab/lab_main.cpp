// minecrappy-lab: the physics without graphics. Everything lives in src/lab (lab::runLab), so tests can
// drive the same command line in-process; this file only hands over the arguments and the version.
#include "lab/lab_cli.h"

int main(int argc, char** argv) { return lab::runLab(argc, argv, MC_VERSION); }
