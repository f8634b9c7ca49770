#version 450
#extension GL_GOOGLE_include_directive : require
#define OIT
#include "mesh_fs.glsl"
