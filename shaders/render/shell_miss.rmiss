#version 460
// Miss shader of the pipeline tracer: nothing to do (the payload already says "no crossing"), but
// the shader binding table needs a miss record for rays that meet nothing.
#extension GL_EXT_ray_tracing : require

void main() {}
