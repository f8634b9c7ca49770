#version 450
#extension GL_GOOGLE_include_directive : require
#define WIREFRAME
#include "mesh_vs.glsl"
