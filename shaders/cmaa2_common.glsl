// CMAA2 (shaders/cmaa2_*.comp): the edge image's bits, one R8UI texel per pixel. A pixel stores the
// edges on its right and bottom sides; its left and top edges are its neighbours' right and bottom.
const uint EDGE_RIGHT = 1u;
const uint EDGE_BOTTOM = 2u;
