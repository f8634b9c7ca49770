#version 450
#extension GL_GOOGLE_include_directive : require
#define WIREFRAME
#include "mesh_fs.glsl"
