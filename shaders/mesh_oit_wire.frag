#version 450
#extension GL_GOOGLE_include_directive : require
#define OIT
#define WIREFRAME
#include "mesh_fs.glsl"
