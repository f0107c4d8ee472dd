#include "viz/canvas.h"
