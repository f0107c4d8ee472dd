#include "world/svg/svg_parse.h"
