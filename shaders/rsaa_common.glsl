// RSAA (Reshetov 2012): the similarity of two geometric samples, shared by the pre-pass and the resolve.
// Must match rsaa_sadp() in engine/methods/rsaa_table.c.

#define RSAA_SIMILARITY_SADP 0
#define RSAA_SIMILARITY_DEPTH 1
#define RSAA_BACKGROUND_DIFF 8.0 // foreground vs background outweighs any SADP (at most 2)

// Sum of absolute dot products: (|n1.r| + |n2.r|) / |r|, r = p2 - p1. 0 on one plane, symmetric, and
// independent of the camera. Positions closer than float precision carry no direction: 0.
float rsaa_sadp(vec3 p1, vec3 n1, vec3 p2, vec3 n2)
{
	vec3 r = p2 - p1;
	float len = length(r);
	float scale = max(max(abs(p1.x), abs(p1.y)), max(abs(p1.z), 1.0));
	if (!(len > 1e-6 * scale))
		return 0.0;
	return (abs(dot(n1, r)) + abs(dot(n2, r))) / len;
}

// The depth-only measure (Deferred MSAA's kind): relative difference of view depths, scaled so that a 2%
// gap reaches the 0.4 threshold; blind to corners whose sides meet at equal depth.
float rsaa_depth_diff(vec3 p1, vec3 p2, vec3 camera, vec3 forward)
{
	float z1 = dot(p1 - camera, forward), z2 = dot(p2 - camera, forward);
	float z = max(max(abs(z1), abs(z2)), 1e-6);
	return min(20.0 * abs(z1 - z2) / z, 2.0);
}

// Difference of two foreground samples by the chosen measure.
float rsaa_diff(int similarity, vec3 p1, vec3 n1, vec3 p2, vec3 n2, vec3 camera, vec3 forward)
{
	return similarity == RSAA_SIMILARITY_DEPTH ? rsaa_depth_diff(p1, p2, camera, forward)
						   : rsaa_sadp(p1, n1, p2, n2);
}
