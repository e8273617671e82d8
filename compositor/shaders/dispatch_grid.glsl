// Numbering of the groups of a one-dimensional dispatch that vk::ComputePipeline::dispatchItems
// lays out in rows (vk::groupGrid: a device need take no more than 65 535 groups in a dimension,
// and a 2048² image at 64 pixels per group is 65 536). The last row may run past the items: a
// shader returns there.
#ifndef SM_DISPATCH_GRID_GLSL
#define SM_DISPATCH_GRID_GLSL

uint smGroupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// The invocation's index over the whole dispatch of one-dimensional workgroups of `groupSize`.
// Callers pass gl_WorkGroupSize.x from main: this file is included before the shader declares its
// local size, and gl_WorkGroupSize read here would be (1, 1, 1).
uint smInvocationIndex(uint groupSize) { return smGroupIndex() * groupSize + gl_LocalInvocationIndex; }

#endif
