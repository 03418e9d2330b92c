#include "app/commands.h"

int main(int argc, char** argv) { return rayster::app::run(argc, argv); }
