/* Failures of a verdict that docs/hard-cases.md ("Expected exceptions") documents, as
 * {scene, method name, verdict, reason}; included by verdicts.c. Keep in step with the docs. */
{"hdr-fireflies", "asaa", AA_VERDICT_VS_NONE,
 "history accumulated in linear HDR: a jittered hit on a 1e3-1e5 emitter stays in the history as a white blob "
 "wider than the emitter for several frames (fireflies); asaa:tonemapped_resolve=true (Karis-weighted) holds"},
{"hdr-fireflies", "taa", AA_VERDICT_VS_NONE,
 "with tonemapped_resolve=false (linear HDR): a jittered hit on a 1e3-1e5 emitter stays in the history as a white "
 "blob wider than the emitter for several frames, and emitters the jitter missed vanish; the default "
 "(Karis-weighted) holds"},
{"hdr-fireflies", "taa-sobel", AA_VERDICT_VS_NONE,
 "as taa: with tonemapped_resolve=false, history accumulated in linear HDR spreads 1e3-1e5 emitters into blobs"},
