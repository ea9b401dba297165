/* Failures of a verdict that docs/hard-cases.md ("Expected exceptions") documents, as
 * {scene, method name, parameter and value (NULL, NULL: any configuration; else only with that
 * parameter at that value, as `aalab methods` writes it), verdict, reason}; included by verdicts.c. Keep in step with the docs. */
{"hdr-fireflies", "asaa", "tonemapped_resolve", "false", AA_VERDICT_VS_NONE,
 "history accumulated in linear HDR: a jittered hit on a 1e3-1e5 emitter stays in the history as a white blob "
 "wider than the emitter for several frames (fireflies); asaa:tonemapped_resolve=true (Karis-weighted) holds"},
{"hdr-fireflies", "taa", "tonemapped_resolve", "false", AA_VERDICT_VS_NONE,
 "with tonemapped_resolve=false (linear HDR): a jittered hit on a 1e3-1e5 emitter stays in the history as a white "
 "blob wider than the emitter for several frames, and emitters the jitter missed vanish; the default "
 "(Karis-weighted) holds"},
{"hdr-fireflies", "taa-sobel", "tonemapped_resolve", "false", AA_VERDICT_VS_NONE,
 "as taa: with tonemapped_resolve=false, history accumulated in linear HDR spreads 1e3-1e5 emitters into blobs"},
{"hdr-fireflies", "asaa", NULL, NULL, AA_VERDICT_DIP,
 "a jittered hit on a 1e3-1e5 emitter held in a quadrant history: one frame 3.6-4.5 dB under none, also with "
 "tonemapped_resolve=true, whose mean holds"},
{"hdr-fireflies", "taa", "tonemapped_resolve", "false", AA_VERDICT_DIP,
 "with tonemapped_resolve=false only: an emitter the jitter hit held in linear HDR history, 3.4 dB under none in "
 "one frame"},
{"hdr-teleport", "asaa", NULL, NULL, AA_VERDICT_DIP,
 "the camera teleports without a cut: the four quadrant histories reproject the old view, 2.1 dB under none in "
 "the frame after the jump"},
{"fast-ball", "asaa", NULL, NULL, AA_VERDICT_DIP,
 "a ball that moves its own width a frame and, on cut-swing, a fast swing after the cut: the quadrant histories "
 "leave ghosts of the ball and the poles, up to 2 dB under none in single frames"},
{"thin-wires", "taa", "tonemapped_resolve", "false", AA_VERDICT_DRIFT,
 "with tonemapped_resolve=false only: a production resolve never settles on sub-pixel wires (it clips every "
 "frame), its PSNR wanders by 3 dB from frame to frame on a still camera, so two quarters can differ by 0.8 dB"},
