// Karis-weighted resolves (Karis 2014), behind the tonemapped_resolve option of taa (taa_converge.glsl)
// and asaa (asaa.comp): a colour's weight in every sum and blend is 1/(1 + luma), so a sample of an HDR
// emitter counts about as much as a white one instead of 1e4 times more. The includer defines
// RESOLVE_KARIS, whether the option is on (uniform), and RESOLVE_LUMA(c), the luma it weights by.

float resolve_weight(vec3 c)
{
	return RESOLVE_KARIS ? 1.0 / (1.0 + RESOLVE_LUMA(c)) : 1.0;
}

// mix(a, b, k) with those weights: k is b's share before weighting
vec3 resolve_mix(vec3 a, vec3 b, float k)
{
	if (!RESOLVE_KARIS) // the plain mix, bit for bit
		return mix(a, b, k);
	float wa = (1.0 - k) * resolve_weight(a), wb = k * resolve_weight(b);
	return (wa * a + wb * b) / (wa + wb);
}
