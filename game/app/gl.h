#pragma once
// OpenGL 3.3 core entry points. Linux's GLVND libOpenGL exports every core function, so the
// prototypes are declared directly (GL_GLEXT_PROTOTYPES) and no loader library is needed.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
