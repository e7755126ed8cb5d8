/**
 * \file collide.hpp
 * \brief Binary inelastic collisions of smooth hard spheres and the two homogeneous DSMC schemes.
 *
 * **Collision rule** (Bodrova and Osinsky 2024, eq. (3), Montanero and Garzo 2002, eqs. (23)-(24); \ref cm_rule "docs/collision-model.md"). For particles a (species k)
 * and b (species j), g = v_a - v_b and e a unit vector along the line of centres:
 *   v_a' = v_a - mu_jk (1 + alpha_kj) (g.e) e,   v_b' = v_b + mu_kj (1 + alpha_kj) (g.e) e,
 * with mu_kj = m_k/(m_k + m_j). Momentum is conserved, (g'.e) = -alpha (g.e), and the energy
 * lost is (1 - alpha^2) m_kj (g.e)^2 / 2.
 *
 * **Rates** (\ref cm_pair_rate "docs/collision-model.md"). A species-k particle meets species-j partners at the rate
 * n_j pi sigma_kj^2 chi_kj <|g|>: one unordered pair collides at pi sigma_kj^2 chi_kj |g| / V, or
 * equivalently at 2 pi sigma_kj^2 chi_kj |g.e| / V with e uniform on the full sphere.
 *
 * **Scheme `majorant`** (DSMC notes, the algorithm of its steps 1-13 with the rate of \ref cm_pair_rate "docs/collision-model.md").
 * Candidate pairs (a, b), a != b uniform among all particles, arrive at the total rate
 *   R = N n B / 2,   B = max_kj pi sigma_kj^2 chi_kj (vmax_k + vmax_j)    (DSMC notes, eq. (8), \ref sch_majorant "docs/schemes.md", N^2 F_N/V_c = N n)
 * where vmax_k is the largest speed of species k, so that B >= (sigma g)_kj for every pair: the
 * majorant is exact, not an estimate. A candidate is accepted with probability
 * pi sigma_kj^2 chi_kj |g| / B (DSMC notes, eq. (7), \ref sch_majorant "docs/schemes.md"), and e is then drawn with density proportional to
 * (g_hat . e) on the hemisphere (\ref cm_hemisphere "docs/collision-model.md"), which samples the same process as the DSMC notes' step 9
 * with the correct rate, at twice its acceptance. A post-collision speed above vmax_k raises the
 * bound at once ("(sigma g)_max raised when exceeded"); the bound is recomputed exactly (lowered as
 * the gas cools) at the start of each time step.
 *
 * **Scheme `pairs`** (Montanero and Garzo 2002, sec. 3, \ref sch_pairs "docs/schemes.md"). For each ordered species pair (i, j), candidates arrive at
 * R_ij = (1/2) N_i omega_max^(ij), omega_max^(ij) = 4 pi sigma_ij^2 n_j chi_ij (vmax_i + vmax_j); a
 * candidate is a random particle of species i, a random other particle of species j and a direction
 * e uniform on the sphere, accepted with probability Theta(g.e) omega_kl / omega_max^(ij),
 * omega_kl = 4 pi sigma_ij^2 n_j chi_ij |g.e|. Montanero and Garzo 2002 sweeps the four pairs one after another in a
 * step; here the pair of each candidate is drawn with probability R_ij / sum R, which samples the
 * same rates without the operator-splitting error of a sweep (\ref sch_thinning "docs/schemes.md").
 *
 * **Scheme `lowrank`** (Bodrova and Osinsky 2024, sec. II B, eqs. (9)-(14) with \ref sch_lowrank_decomposition "docs/schemes.md", \ref sch_lowrank "docs/schemes.md"). The ordered species pair
 * (i, k) of a candidate is drawn with probability A_ik / R from the rank-3 majorant
 * A_ik = pi sigma_ik^2 chi_max w_i N_i N_k / V, w_i = vmax_i, through segment trees in O(log M)
 * (segment_tree.hpp, which derives the decomposition); then a particle of each species, uniformly
 * (the same particle twice is rejected), accepted with chi_ik |g| / (chi_max (w_i + w_k)), and e drawn
 * as in `majorant`. V = (N - 1)/n gives every particle pair the candidate rate of `majorant`, so the
 * two schemes sample exactly the same process. A raised vmax_i updates species i's row in O(log M).
 * (For very many species the S x S pair tables below are the next limit: issue 4.)
 *
 * **Restitution.** Constant alpha_kj, or viscoelastic (Bodrova and Osinsky 2024, eqs. (5)-(8), \ref visco_series "docs/viscoelastic.md"): alpha from the
 * normal impact speed |g.e| of each collision (restitution.hpp). The bounds and the acceptance do not
 * change: only the collision rule does (Bodrova and Osinsky 2024, sec. II, \ref sch_lowrank "docs/schemes.md").
 *
 * **Displacements** (Bodrova and Osinsky 2024, eq. (15), \ref sch_displacements "docs/schemes.md"), when the System tracks them: at a collision at
 * time t both partners add their free flight v (t - t_last) to R before their velocities change.
 *
 * **Time.** All schemes are uniformised continuous-time processes: each candidate advances time by
 * 1 / R (the mean waiting time; the N_p = R dt candidates of the DSMC notes, eq. (8), \ref sch_majorant "docs/schemes.md" per step, with the
 * fraction carried over). Collisions are processed one after another with current velocities, so
 * there is none of the batch time-step bias of \ref sch_thinning "docs/schemes.md". The time step dt only sets how often the
 * bounds are recomputed: dt = step_fraction / nu_max, nu_max = 2 R / N the majorant collision
 * frequency of one particle (the majorant mean free time). It is written to the output.
 *
 * **Look-ahead** (performance, no change to the process). The particle indices of the next
 * `lookahead` candidates are drawn in advance and their velocities prefetched, so that the memory
 * reads of many candidates overlap: with 1e6 particles the velocities do not fit in cache and a
 * candidate would otherwise wait for two memory reads in turn. A candidate pair is drawn
 * independently of the particles' state (uniformly in `majorant`; from A_ik in `lowrank`), so drawing
 * it earlier does not change its distribution; `lowrank` discards its drawn-ahead pairs whenever
 * A_ik changes, since they were drawn from the old rates, and discarding independent draws biases
 * nothing. The drawn-ahead pairs are part of the collider's state (State below). The block kernels
 * draw 8 ahead, or 32 in a frame (thermostat and shear stages, "Frame"): a stage gives each block only
 * about N_b/16 candidates, so its velocities are not in the cache and each read waits for memory
 * (uniform shear flow, N = 1e6, one thread, whole runs: 32 ahead take 0.87 of the time of 8; the
 * stream's draws then fall differently, so such runs are no longer byte for byte those of before).
 *
 * **Blocks** (issue 5; one species, or a mixture of at most 128 species, with `majorant` or `lowrank`;
 * N >= 2 block_size; `use_blocks`). With
 * 1e6 particles the velocities (24 MB) do not stay in the caches and every candidate waits for
 * memory. The particles are therefore split into K = N / block_size contiguous blocks, and during
 * a time step each block is a gas of its own: its candidates are pairs of its own N_b particles at
 * R_b = N_b n B_b / 2 with its own bound B_b = 2 pi sigma^2 chi vmax_b, so that every particle keeps
 * the collision frequency n pi sigma^2 chi <|g|> of the whole gas (the pair rate is
 * pi sigma^2 chi |g| n/(N_b - 1) instead of n/(N - 1): a homogeneous gas of N_b particles at density
 * n). Each block is an unbiased sub-sample of the homogeneous gas. The blocks run one after another
 * over the step, each from the step's start to its end, so all of them are at the same time at
 * every step end (and at every time target). Between steps the particles are dealt round the blocks
 * like cards from a random starting point (`remix`): each new block takes every K-th particle of
 * every old one, so the blocks never keep their members and no correlation builds up within one.
 * The dealing is done in place (deal.hpp, issue 11): the rows of K particles, read from the starting
 * point, are transposed into the K blocks, tile by tile through a buffer onto a grid of runs of 64
 * particles, and the runs are then permuted along the cycles of the transposition, with scratch memory
 * of a few tiles (below 0.7 bytes a particle for blocks of 32768) instead of a second copy of the
 * velocities (24 bytes a particle) and displacements (32). It moves the same bytes to the same places
 * as dealing into a second array, so every output is unchanged.
 * What changes against the unblocked gas is the number of possible partners between remixes,
 * N_b - 1 instead of N - 1, a finite-N effect of order 1/N_b (block_size 32768 by default); the
 * validation cases `*_blocks_quick` (haff_cooling, collision_rate) compare blocked runs with the
 * same theory at the same tolerances. With one species the rank-3 majorant of `lowrank` is the
 * uniform one, so both schemes run the same blocked loop. The block's bound is recomputed exactly at
 * its first visit in a step (a pass in order over the block, which is also what brings it into the
 * cache). **Step length** (block_step_length; \ref sch_blocks "docs/schemes.md", "Step length"): a
 * step costs a remix and that pass, and within it a block's bound is only raised, so that it loosens as
 * the gas cools; one collision per particle dissipates at most gamma = max (1 - alpha_kj^2)/3 of the
 * energy, and a step of c = min(sqrt(2/gamma), 6) collisions per particle balances the two (the measured
 * remix-and-pass cost, half that of one collision per particle): c/p majorant mean free times at the
 * last step's acceptance p, never less than block_steps = 5 (about one collision per particle), times
 * step_fraction, and of at most max_block_step_candidates = 3/4 of 2^24 candidates unless block_steps
 * is more (N > 5e6: the steps of before, which the simulation's chunks of 2^24 candidates split as
 * before above N = 6.7e6; the first step is capped too). Viscoelastic restitution and
 * frames keep block_steps. The length sets when bounds are refreshed and blocks remixed, not the process. Event targets
 * are met exactly all the same (collision-driven runs, `collisions_per_particle`): at the start of a
 * step, when fewer events are left to the target than the step could bring (its candidates R dt times
 * the acceptance of the last step, 1 for the first step of a run, plus 10 % and 8 standard
 * deviations), the step is shortened to fit; when that would leave it fewer than min(N/64, 4 N/K)
 * events, the step runs instead on the whole gas as one block, with the exact bound of all particles,
 * and stops at the target. The time step only sets when bounds are refreshed and blocks
 * remixed, so its length may change from step to step without changing the process. Such a step samples the unblocked process exactly, so the
 * mixture of blocked and whole-gas steps is as unbiased as either. Soft targets (the progress and
 * checkpoint chunks of the simulation) are checked at step ends only.
 *
 * **The one-species block kernel** (issue 11; `run_block_one_species`). A block of one species with
 * constant restitution runs a loop of its own, which samples exactly the process of `majorant` above
 * (the same candidate rate R_b, uniform pairs, acceptance |g| / (2 vmax_b), e of density (g_hat.e)/pi,
 * bounds raised when exceeded, candidate times t0 + (c + 1)/R_b) with less work per candidate and per
 * collision: the pair's two indices from the halves of one 64-bit draw (rng::Xoshiro256pp::below_pair,
 * exactly uniform by rejection), the drawn-ahead pairs in local variables, no species or viscoelastic
 * branches (a frame is a template parameter: "Frame" below), and the impulse from p = (g.e) e = (g + |g| w)/2 for e = (g_hat + w)/|g_hat + w|
 * (hemisphere_projection): no e is formed, so no second root nor division, with w from
 * rng::unit_vector_32 (one draw per try; directions on a lattice of step 2^-31, about 1e-9 rad). The
 * random stream differs from run_majorant's, the law of the process does not; blocks still draw only
 * from their own streams (bitwise the same for any thread count). Viscoelastic restitution (whose alpha
 * needs g.e) runs run_majorant / run_lowrank in its blocks; mixtures have a kernel of their own
 * ("Mixtures in blocks"). Measured at N = 1e6 (CPU time,
 * medians, both builds alternately): 4.49 candidates per collision as before, 31 ns per candidate before
 * and 19 after, 1.6 times the collisions per second of bench_collide and 1.9 times end to end
 * (bench_paths, one species, t_end). Tighter majorants were tried and left out (\ref sch_blocks "docs/schemes.md",
 * "The one-species kernel"): speed classes cut the candidates per collision to 1.5-1.7 and a single
 * fast layer to 2.5, but their pair law depends on the velocities, so pairs can no longer be drawn
 * ahead and prefetched, and each candidate costs more than the rejections saved.
 *
 * **Frame** (`set_frame`; the stage loop of thermostat.hpp). A uniform shear flow's streaming and a
 * thermostat's rescaling act on every velocity alike, V -> L V with one linear map L per stage.
 * Instead of a pass over all particles per stage, the System may hold the velocities u in a frame,
 * the actual peculiar velocity being
 *   V = G u,   G = S [[1, c, 0], [0, 1, 0], [0, 0, 1]]   (V_x = S (u_x + c u_y), V_y = S u_y, V_z = S u_z),
 * and a stage then changes only G: a rescaling by s multiplies S by s, the streaming V_x -> V_x - a dt V_y
 * subtracts a dt from c (both maps are of this form, and so are their products). The u change only at
 * collisions. A candidate's relative velocity is g = G (u_a - u_b) and the collision is computed from it
 * exactly as above (acceptance, e, g.e, the energy loss); the partners' u change by the impulse mapped
 * back, -/+ mu (1 + alpha)(g.e) G^-1 e, G^-1 e = (e_x - c e_y, e_y, e_z)/S. The process is therefore the
 * same as with the velocities updated in every stage; only the round-off differs. The bounds hold the
 * largest |u| of each species, and a relative speed is bounded by |G (u_a - u_b)| <= ||G|| (|u_a| + |u_b|),
 * ||G|| = S (|c|/2 + sqrt(1 + c^2/4)) the largest singular value of G: every bound is multiplied by
 * ||G||, which the stage loop keeps within 2 % of S by bringing the velocities back to G = 1 (one pass)
 * whenever |c| exceeds 0.04 and at every sample. The frame's second moments Q = sum m u u^T (xx, yy,
 * zz, xy) are kept up to date collision by collision, so that the thermostat knows the kinetic energy
 * S^2 (Q_xx + 2 c Q_xy + c^2 Q_yy + Q_yy + Q_zz)/2 of every stage without a pass. Constant restitution
 * and no displacement tracking (what the stage loop runs). **Frames in blocks** (issue 11; `majorant`
 * or `lowrank`, one species or a mixture): the frame is the whole gas's, so every block of a pass uses
 * the same G (each worker takes it from the master at the start of its block). The block kernels
 * (run_block_one_species, run_block_mixture) take it as a template parameter: g = G (u_a - u_b), the
 * block's bound (or each w_i of its A_ik) times ||G||, the impulse mapped back with G^-1 (applied to
 * (g.e) e itself, which hemisphere_projection gives), and the block's change of Q summed in the kernel
 * and added to the master's in block order after the pass, so Q, like the counts, is the same bit for
 * bit on any thread count. A stage is usually far shorter than a blocked step (0.125 against 5
 * majorant mean free times), so a pass covers one stage and a block is remixed every ~40 stages; the
 * kernels' drawn-ahead, prefetched pairs keep such short visits fast. When the stage loop applies the
 * frame to the velocities (reset_frame) each block's bound is recomputed by a pass over it. Measured at
 * N = 1e6: docs/shear-viscosity.md, "Cost".
 *
 * **Mixtures in blocks** (issue 11). Block j holds a slice of every species: species k's particles
 * are dealt round K slices inside species k's own range (so the species layout of the System never
 * changes), ceil((N_k - j)/K) of them in block j, when N_k >= min_slice K (min_slice = 64). A rarer
 * species is *scattered* instead: at every remix its particles are put in a uniformly random order
 * (Fisher-Yates) and cut into K slices of multinomial counts, i.e. each particle goes to a uniformly
 * random block independently of all others (the first step draws the counts only: the initial order
 * is independent of the velocities). Dealing a species with fewer than K particles would put them in
 * the first blocks and never two of them together, and one with a few per block would meet itself at
 * n (N_kb - 1)/(N_b - 1), a relative error 1/N_kb; scattered, any two particles share a block with
 * probability 1/K, and E[1/(N_b - 1) | both in b] = K/(N - 1) for independent placements, so the
 * expected pair rate is the gas's. The counts are part of the State. A block is then a mixture of N_b
 * particles in the gas's proportions, run exactly as the unblocked `majorant` scheme with its own bound
 * B_b = max_kj pi sigma_kj^2 chi_kj (vmax_bk + vmax_bj) over the species present in it and rate
 * R_b = N_b n B_b / 2: a candidate is a uniform pair of the block's particles (an index into the
 * block's slices). Each species-k particle meets species-j partners at n N_jb/(N_b - 1) instead of
 * n N_j/(N - 1): the finite-N effect of the one-species blocks, of relative order 1/N_b on average
 * (dealt slices differ from N_j/K by less than one particle; scattered ones are unbiased). With `lowrank` each block samples its own majorant A_ik of its slices, in the form
 * of segment_tree.hpp (A_ik = pi sigma_ik^2 chi_ik w_i N_i N_k / V, accepted with |g| / (w_i + w_k)), but
 * with each of the at most 128^2 entries computed exactly and chi_ik itself in place of chi_max: N_k the
 * slice's count, V = (N_b - 1)/n and w_k = vmax_k the block's, so that again each pair's rate is
 * pi sigma_ik^2 chi_ik |g| n/(N_b - 1) (the two orders (a, b) and (b, a) add w_i + w_k). The species
 * pair (i, k) of a candidate is drawn with probability A_ik / R_b from an alias table of the P^2
 * entries of the P species present in the block (rebuilt when a bound is raised), then a particle of slice i and one of slice k; the
 * whole-gas steps near event targets run the unblocked `lowrank` loop.
 * With constant restitution a mixture's block runs a kernel of its own (issue 11; `run_block_mixture`,
 * for `majorant` and `lowrank`), which samples exactly the process just described (the same R_b, the
 * same pair law, the same acceptance, bounds raised when exceeded, `lowrank`'s drawn-ahead pairs
 * redrawn when A_ik changes) with the techniques of the one-species kernel: the two indices of a pair
 * from one draw (below_pair: two block indices in `majorant`), the drawn-ahead pairs in locals with
 * their species, which the slice of an index gives (no read of the species array), each species pair's
 * constants in one record (PairKernel), the block's generator in a local copy (its state in registers,
 * not stored and reloaded at every draw), no viscoelastic branch (a frame: a template parameter), and the impulse from
 * hemisphere_projection. A `lowrank` candidate is one 64-bit word too (set_block_lowrank lays the
 * block's alias table over 2^m >= max(P^2, 2) cells, zero weights after the P^2 pairs, each pair's two
 * slices, Lemire thresholds and w_i + w_k in one record): the cell from the top m bits, its coin from
 * the next 16 - m (a further uniform only when they tie with the threshold's leading bits, so the coin
 * is exact), the two particles from two 24-bit fields by multiply-shift with rejection (below_pair's,
 * in 24 bits; a block with a slice of 2^24 or more has every rejection threshold at 2^24, so that
 * below_pair draws each of its candidates). Viscoelastic mixtures run the general loops in their blocks.
 * *The cheaper sampler* (issue 11, 2026-11-28). In a block both samplers are exact for the same pair law
 * (each pair at pi sigma_ik^2 chi_ik |g| n/(N_b - 1)): a majorant sets only how many candidates a
 * collision takes, not the process. So a mixture's blocks run whichever costs less, whatever the
 * scheme: at each step, from the gas's bounds vmax_k, `lowrank` when lowrank_candidate_cost (1.15, a
 * `lowrank` candidate's cost over a `majorant` one's in the kernel) times its candidate rate
 * sum_ik pi sigma_ik^2 chi_ik vmax_i N_i N_k n/(N - 1) is less than the `majorant` rate N n B/2
 * (block_candidate_rate). The master chooses once per step for all blocks (so that R, the last step's
 * acceptance and the output do not depend on the threads); the choice is part of the State. A step
 * whose sampler differs from the one the last step ran (a change of choice, or after a whole-gas step,
 * which runs the scheme's) judges its events near an event target from the last step's events per unit
 * time (the last step's acceptance was another majorant's) and is 5 mean free times long. Masses 1 and 4 with diameters 1 and 1.5 (bench_paths' binary gases) take `majorant`,
 * diameters 1 and 2 and many species of unlike sizes `lowrank`. Viscoelastic mixtures and whole-gas
 * steps keep the scheme's own loops, as does every unblocked run; set_block_sampler() forces one sampler
 * (the kernel tests, bench_collide's `scheme`). Tested in Collide.BlocksRunTheCheaperSampler (the rates
 * by hand, the choice, samplers changed step by step against the unblocked gas, restore).
 * What a mixture candidate costs beyond a one-species one was cut further on 2026-11-27 without
 * changing a single draw (the output of 16 runs byte for byte the same): a `majorant` candidate's
 * species from 32-bit edges held in locals (species_at: one compare for two species, a search without
 * mispredictions above 8) and its system index by one add; a drawn-ahead candidate carries its pair's
 * index (its species looked up only after a collision); `lowrank`'s alias coin selects the outcome by a
 * mask, since a branch on it went either way at random; (pi sigma^2 chi)^2 kept per pair. On
 * 2026-11-28, again without changing a draw: the drawn-ahead candidates in three arrays of 32-bit words
 * (a record of 12 bytes took extra instructions to address), the acceptance's constants in arrays of
 * their own (pair_cross_section2_, pair_limit_; PairKernel is read only for a collision), and a kernel
 * for a binary `majorant` mixture (`Two`) with its edge and offsets in registers: 10 % fewer
 * instructions in that kernel, 5 % in `lowrank`'s. Measured in docs/schemes.md ("Cache blocks") and
 * README ("Performance").
 * Why a `lowrank` candidate cost more than a `majorant` one (issue 11: 40 against 23 ns in a loaded
 * session, 23.7 against 17.9 in the session below; perf on bench_collide, binary lowrank): its pair
 * draw was half of the kernel's samples (49 %, `majorant`'s 25 %), a dependent chain before the
 * particles could be prefetched: a 53-bit uniform converted to double, scaled, truncated and clamped,
 * the alias threshold read and compared (a branch), the alias read, the pair's species read, the four
 * slice bounds read and subtracted (spilled to the stack), then a second draw for below_pair. The
 * one-word draw above cut that share to 33 % (about 9.5 -> 5 ns); the rest of a candidate (the
 * velocities, the acceptance, whose branch goes either way, and a collision's two roots) is
 * `majorant`'s. Measured at N = 1e6 (bench_collide 1000000 0.9 10 32768, the binary gases of
 * bench_paths, CPU time, commit 8531ce2 and this code alternately three times, load about 5 on 2
 * cores, medians): `lowrank` 23.7 -> 18.7 ns per candidate (1.00e7 -> 1.26e7 collisions/s, 0.62 ->
 * 0.78 of the one-species rate; Enskog 23.4 -> 18.9, 0.63 -> 0.79), `majorant` 17.9 -> 17.2 ns (1.26e7
 * -> 1.30e7, 0.77 -> 0.82; Enskog 0.77 -> 0.82), one species 14 ns; candidates per collision 4.23
 * (`lowrank`) and 4.45 (`majorant`), unchanged. So in blocks the two schemes now cost within 4 % the
 * same per collision (79 and 77 ns: `lowrank`'s 5 % fewer candidates for its 9 % dearer candidate, the
 * record reads and the wider draw). End to end (bench_paths 1000000, medians of three, each over the
 * one-species `t_end` run of the same process): the collision loop's rate (wall clock) `lowrank` 0.63 ->
 * 0.85 (Enskog 0.64 -> 0.86), `majorant` 0.76 -> 0.84 (Enskog 0.76 -> 0.78); collisions per CPU second
 * of the whole run `lowrank` 0.70 -> 0.81 (Enskog 0.69 -> 0.80), `majorant` 0.83 -> 0.83 (Enskog 0.79 -> 0.80). Tried and left out: a look-ahead of 16 instead of 8 (no gain: a block's
 * velocities are in L2; in a frame they are not, and 32 are drawn ahead: "Look-ahead").
 * Checked by Collide.BlockedMixtureMatchesUnblocked (T_k, the share of unlike-pair events, the time at
 * an event target, over 16 replicas, both schemes), Collide.BlockedThreeSpeciesLowrankMatchesUnblocked
 * (three species: 16 alias cells for 9 pairs; T_k and each pair's share of events) and by every
 * mixture validation, which runs blocked at N >= 2 block_size. Measured at N = 1e6 (binary, masses 1
 * and 4, diameters 1 and 1.5, one replica) before the kernels: 5.5e6 collisions/s blocked against 2.1e6
 * unblocked.
 *
 * **Threads inside one replica** (issue 11; `use_threads`). Within a blocked step the blocks are
 * independent gases over the same time interval: block j reads and writes only its own particles, its
 * own bound vmax_jk and its own carried credit. They therefore run on OpenMP threads, each thread on a
 * copy of this collider's pair tables (a "worker"). For the output not to depend on the thread count,
 * nothing a block draws comes from a shared stream: at the start of each pass over the blocks (a step,
 * or the part of one up to a time target) a 64-bit key is drawn from the replica's collision stream,
 * and block j draws from its own xoshiro256++ stream seeded by a hash of (key, j)
 * (rng::Xoshiro256pp::substream), i.e. keyed by (seed, replica, pass, block). Each block's counts and
 * sums (events, candidates, pair events, dissipated energy, overshoots) are kept apart and added to
 * the replica's in block order after the pass, so that every floating-point sum is the same for one
 * thread or many. Only the whole-gas steps near event targets run on one thread; the remix between
 * steps is a fixed permutation, and two of its four in-place stages are split over the threads
 * (deal.hpp, "Threads"): whichever thread moves a particle, it ends in the same place. The streams
 * of distinct (key, j) are distinct seeds of a generator of period 2^256 - 1 drawn about 1e5 times
 * each per pass: they overlap with a probability below 1e-60 in any run that could be executed.
 *
 * Units: the user's; time in the user's time unit, e.g. sigma sqrt(m/T0).
 * Checked by tests/collide_test.cpp and validation/ (haff_cooling, collision_rate, schemes_agree).
 */
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dsmc/deal.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/rules.hpp"
#include "dsmc/segment_tree.hpp"
#include "dsmc/state.hpp"
#include "model/species.hpp"

namespace gdsmc::collide {

enum class Scheme { majorant, pairs, lowrank };

/// Per-species-pair event counts are kept for mixtures of at most this many species.
inline constexpr std::size_t pair_event_limit = 64;
/// Cache blocks serve mixtures of at most this many species (header "Mixtures in blocks": a block's
/// alias table of the present species' pairs takes at most 14 bits of a candidate's word).
inline constexpr std::size_t block_species_limit = 128;

/// The species of a block's i-th particle in the `majorant` mixture kernel: the k with edge[k] <= i <
/// edge[k + 1], edge the block's running counts (edge[0] = 0 <= i < edge[s]; an empty species has
/// edge[k] = edge[k + 1] and is never returned). Two species: one compare; up to 8: a count of the
/// edges <= i without branches; more: a search whose steps depend on s only, so that none of them is
/// mispredicted (the number of edge[1..s-1] <= i, as std::upper_bound would find it). Tested against
/// counting by hand (Collide.SpeciesOfABlockIndex).
inline std::uint32_t species_at(const std::uint32_t* edge, std::size_t s, std::uint32_t i) {
  if (s == 2) return i >= edge[1];
  std::uint32_t k = 0;
  if (s <= 8) {
    for (std::size_t q = 1; q < s; ++q) k += i >= edge[q];
    return k;
  }
  const std::uint32_t* first = edge + 1;
  std::size_t len = s - 1;
  while (len > 1) {
    const std::size_t half = len / 2;
    first = first[half] <= i ? first + half : first;
    len -= half;
  }
  return static_cast<std::uint32_t>(first - (edge + 1)) + (*first <= i);
}

/// Counts kept by a run: the observables `collisions` and `collisions_pair` come from here.
struct Counters {
  std::uint64_t events = 0;                ///< accepted collisions (binary events)
  std::uint64_t candidates = 0;            ///< candidate pairs tested
  std::vector<std::uint64_t> pair_events;  ///< S x S, events between species k and j at (min, max);
                                           ///< empty above pair_event_limit species
  std::uint64_t steps = 0;                 ///< time steps (bound recomputations)
  double step_sum = 0.0;                   ///< sum of the step lengths, for the mean dt
  double dissipated = 0.0;                 ///< kinetic energy lost so far, (1 - alpha^2) m_kj (g.e)^2/2
                                           ///< per collision (\ref cm_energy "docs/collision-model.md"): the thermostat's loss
  /// Enskog gas in shear flow (set_shear): sum over accepted collisions of m_kj sigma_kj (1 + alpha)
  /// (g.e) e e, components xx, yy, zz, xy, xz, yz: the collisional transfer (\ref eta_pressure "docs/shear-viscosity.md").
  std::array<double, 6> transfer{};
  /// Candidates whose acceptance probability came out above 1 (the bound was not a majorant), and the
  /// largest such probability: an invariant of every scheme, 0 in a correct run (validation/ fails
  /// otherwise, and the program warns).
  std::uint64_t overshoots = 0;
  double largest_acceptance = 0.0;
};

/// The collision stage of one replica: particles, pair constants, bounds, clock and generator.
class Collider {
 public:
  /// `viscoelastic_beta`: beta_ki of the viscoelastic restitution (restitution.hpp), or nullptr
  /// for the constant alpha_kj of the mixture.
  Collider(Scheme scheme, const species::Mixture& mix, particles::System& sys,
           rng::Xoshiro256pp gen, double step_fraction,
           const species::PairMatrix* viscoelastic_beta = nullptr);

  /// Cache blocks of about `block_size` particles (header, "Blocks"), for one species or a mixture of
  /// at most block_species_limit (128) species with the `majorant` or `lowrank` scheme and N >= 2 block_size; otherwise (or
  /// with 0) the whole gas is one block. Call before the first advance().
  void use_blocks(std::size_t block_size);
  std::size_t blocks() const { return block_first_.empty() ? 1 : block_first_.size() - 1; }
  /// Which exact sampler a mixture's blocks run (header "Mixtures in blocks", "The cheaper sampler"):
  /// `cheaper` (the default) takes, at each step, the one of the `majorant` and `lowrank` block majorants
  /// whose candidates cost less in all, whatever the scheme; the other two force one (tests, benchmarks).
  /// Viscoelastic mixtures and the whole-gas steps keep the scheme's own sampler.
  enum class BlockSampler { cheaper, majorant, lowrank };
  /// The sampler of the blocks from the next step on (BlockSampler::cheaper by default).
  void set_block_sampler(BlockSampler sampler) { block_sampler_ = sampler; }
  /// With blocks: whether the blocks of the step under way (or of the last one) run the `lowrank` sampler.
  bool block_lowrank() const { return block_lowrank_; }
  /// The candidate rate of the blocks' `lowrank` (true) or `majorant` sampler, summed over the blocks,
  /// at the gas's speed bounds vmax_k (those of the step under way, or as set_max_speeds() set them),
  /// without a frame's factor: sum_ik pi sigma_ik^2 chi_ik vmax_i N_i N_k n/(N - 1) and N n B/2 with
  /// B = max_kj pi sigma_kj^2 chi_kj (vmax_k + vmax_j) (header "Mixtures in blocks"); the cheaper
  /// sampler is `lowrank` when lowrank_candidate_cost times the first is less than the second.
  double block_candidate_rate(bool lowrank) const {
    return lowrank ? lowrank_block_rate(max_speed2_.data())
                   : 0.5 * static_cast<double>(sys_.size()) * mix_.total_density() * mixture_bound(max_speed2_.data());
  }
  /// A `lowrank` block candidate's cost over a `majorant` one's, both in the mixture kernel (binary
  /// gases at N = 1e6: 1.09 on 2026-11-27, 1.06-1.20 per bench_collide round and 1.18-1.19 from whole
  /// processes on 2026-11-28; docs/schemes.md "The cheaper sampler").
  static constexpr double lowrank_candidate_cost = 1.15;
  /// OpenMP threads for the blocks of a step (header, "Threads inside one replica"); 1 by default.
  /// The results do not depend on it, bit for bit. Without blocks it has no effect.
  void use_threads(int threads);
  /// The threads set by use_threads (1 by default).
  int threads() const { return threads_; }
  /// Memory the collider holds for the particles besides the System, in bytes: the scratch memory of
  /// the blocks' remix, done in place (deal.hpp; about (2 seg + 1) K elements and N/seg bits).
  std::size_t workspace_bytes() const { return remix_workspace_.bytes(); }

  /// Advances until time `t_target` or until `event_target` events, whichever comes first.
  /// Returns true when the event target stopped it. With blocks and `exact_events`, the steps near
  /// the event target run on the whole gas and stop at it exactly (header, "Blocks"); without
  /// `exact_events` (a soft target: a progress or checkpoint chunk) it is checked at the end of
  /// each blocked step only and may be passed by up to one step's events. `event_limit` is a hard
  /// target beyond a soft one (the sample's own event target): never passed, met exactly as an exact
  /// `event_target` is, so that a soft chunk's step cannot run past it. With blocks and `to_step_end`
  /// it also stops at the end of the blocked step under way (or of the one that starts now), so that
  /// a chunk that ends there never splits a step (header, "Blocks"); without blocks `to_step_end` is
  /// ignored.
  bool advance(double t_target, std::uint64_t event_target = UINT64_MAX, bool exact_events = true,
               std::uint64_t event_limit = UINT64_MAX, bool to_step_end = false);

  /// The velocities were changed from outside between two advance() calls (the streaming of a
  /// shear flow, a thermostat's rescaling): the largest speeds and the bounds are recomputed
  /// exactly, O(N), so the majorant holds again. Not with blocks.
  void velocities_changed() {
    recompute_max_speeds();
    rebuild_bounds();
  }
  /// Uniform shear flow u_x = a y in the Enskog gas (`pairs` scheme only; \ref eta_enskog_shear "docs/shear-viscosity.md"): a partner at
  /// r_k + sigma_ij e moves with the flow a sigma_ij e_y relative to particle k, so the relative velocity
  /// of the collision is g = V_k - V_l - a sigma_ij e_y x_hat, in the acceptance Theta(g.e) |g.e| and in
  /// the update; the bound grows by a sigma_ij/2 >= |a sigma_ij e_y e_x|. Each accepted collision adds
  /// its collisional transfer to Counters::transfer. Throws std::invalid_argument for another scheme.
  void set_shear(double rate);
  /// The same when the caller has just computed the largest speed^2 of each species in its own
  /// pass over the particles (thermostat.hpp's fused stage pass): no second pass here.
  void set_max_speeds(const std::vector<double>& max_speed2) {
    for (std::size_t k = 0; k < s_; ++k) {
      max_speed2_[k] = max_speed2[k];
      max_speed_[k] = std::sqrt(max_speed2[k]);
    }
    rebuild_bounds();
  }

  /// The frame of the stored velocities (header, "Frame"): V = S (u_x + c u_y, u_y, u_z), with
  /// S = `scale`, c = `shear`. The first call starts the frame with the moments of the stored u
  /// computed by a pass; later calls only rebuild the bounds (the u are unchanged). Throws
  /// std::logic_error with viscoelastic restitution or displacement tracking.
  void set_frame(double scale, double shear);
  /// The stored u were just replaced by the actual velocities (the frame was applied to them in a
  /// pass that also computed `moments` = sum m V V^T (xx, yy, zz, xy) and the largest speed^2 of
  /// each species): G = 1 again, and the bounds exact (with blocks, each block's by a pass over it).
  void reset_frame(const std::array<double, 4>& moments, const std::vector<double>& max_speed2);
  bool framed() const { return framed_; }
  double frame_scale() const { return frame_scale_; }
  double frame_shear() const { return frame_shear_; }
  /// sum m u u^T of the stored u (xx, yy, zz, xy), kept collision by collision in a frame.
  const std::array<double, 4>& frame_moments() const { return moments_; }
  /// ||G||, the factor of every speed bound in a frame (1 without one).
  static double frame_norm(double scale, double shear) {
    return scale * (0.5 * std::abs(shear) + std::sqrt(1.0 + 0.25 * shear * shear));
  }

  double time() const { return time_; }
  const Counters& counters() const { return counters_; }
  /// Mean length of the time steps so far (0 before the first step).
  double mean_step() const { return counters_.steps ? counters_.step_sum / counters_.steps : 0.0; }
  double candidate_rate() const { return rate_; }
  /// With blocks: the candidates per unit time of the blocked step under way, or of the one that just
  /// ended at a step end (0 before the first candidate); the simulation sizes its chunks with it.
  double recent_candidate_rate() const {
    const double elapsed = time_ - step_start_;
    return elapsed > 0.0 ? static_cast<double>(counters_.candidates - step_candidates_start_) / elapsed : 0.0;
  }

  /// Everything that evolves during a run, for checkpoints. The bounds and samplers are not stored:
  /// they are functions of the speeds vmax_k (rebuilt exactly on restore), and so is every tree
  /// and table of `lowrank` (segment_tree.hpp recomputes its sums from the leaves).
  struct State {
    double time = 0.0, credit = 0.0, next_step_time = 0.0;
    std::vector<double> max_speed, max_speed2;
    Counters counters;
    rng::Xoshiro256pp::State generator{};
    std::vector<std::uint32_t> pending;  ///< the drawn-ahead candidates, 4 per candidate
    std::size_t pending_next = 0;
    bool pending_filled = false;
    std::vector<double> block_max_speed2, block_credit;  ///< with blocks (use_blocks)
    std::vector<std::uint64_t> slice_counts;             ///< with scattered species: each block's counts, K x S
    double step_start = 0.0;                             ///< with blocks: when this step began
    bool whole_step = false;                             ///< with blocks: the step runs on the whole gas
    double step_acceptance = 0.0;
    std::uint64_t step_events_start = 0, step_candidates_start = 0;
    int block_lowrank = -1;  ///< with blocks: the step's sampler (1 `lowrank`, 0 `majorant`; -1 unknown: the scheme's)
    bool framed = false;                                 ///< set_frame: the frame and its moments
    double frame_scale = 1.0, frame_shear = 0.0;
    std::array<double, 4> moments{};
  };
  State state() const;
  /// Continues from `state`, taken from a Collider of the same scheme, mixture and particle counts
  /// at the end of an advance(); the System must hold the particles of that moment.
  void restore(const State& state);
  /// The State under named values "collider/..." (dsmc/state.hpp), for checkpoints.
  void save(state::Record& record) const;
  /// Continues from save()'s record (as restore(State)); throws state::StateError for a missing,
  /// misshapen or impossible value (a drawn-ahead candidate naming no particle, a frame's scale <= 0).
  void restore(const state::Record& record);

 private:
  void recompute_max_speeds();
  void rebuild_bounds();
  bool raise_max_speed(std::size_t particle);
  template <class TryCandidate>
  int run_substep(double t_stop, std::uint64_t event_target, TryCandidate&& try_candidate);
  /// The unblocked loop `loop` (the scheme's, or a whole-gas step's) with the collider's rule, up to
  /// t_stop or the event target (returns a Stop, collide.cpp): the rule_ and the frame dispatched here,
  /// once per sub-step, to the loops that take them as template parameters.
  int run_loop(Scheme loop, double t_stop, std::uint64_t event_target);
  /// On a worker: the current block in the block kernel of `rule` (one species or a mixture,
  /// `lowrank`'s sampler or `majorant`'s), for a rule with the projection (rules.hpp).
  template <class Rule>
  void run_block_kernel(const Rule& rule, bool lowrank, double t_stop);
  template <class Rule, bool Framed>
  int run_majorant(const Rule& rule, double t_stop, std::uint64_t event_target);
  bool advance_blocks(double t_target, std::uint64_t event_target, bool exact_events, std::uint64_t event_limit,
                      bool to_step_end);
  /// The length of a blocked step that starts now at candidate rate `rate` (header "Blocks", "Step length");
  /// `acceptance_unknown`: the last step's acceptance is another sampler's (block_steps mean free times).
  double block_step_length(double rate, bool acceptance_unknown = false) const;
  void set_whole_gas_bound();       ///< bound_, rate_ and range of a whole-gas step (with blocks)
  bool whole_step_ = false;         ///< with blocks: this step runs on the whole gas (near an event target)
  double step_acceptance_ = 0.0;    ///< with blocks: events per candidate in the last step
  std::uint64_t step_events_start_ = 0, step_candidates_start_ = 0;  ///< counters at this step's start
  void remix();
  // Blocks (empty block_first_: none). Candidates are drawn in [range_first_, + range_count_).
  std::vector<std::size_t> block_first_;  ///< K + 1 boundaries
  std::vector<double> block_max_speed2_;  ///< vmax_k^2 of each block and species, K x S (raised within a step)
  std::vector<double> block_credit_;      ///< each block's carried candidate time
  std::size_t current_block_ = 0;
  /// A worker running block j (run_block): the block's vmax_k^2, in the master's block_max_speed2_.
  double* block_speed2_ = nullptr;
  // Threads inside one replica (header): the workers, and each block's counts of the current pass.
  int threads_ = 1;
  std::vector<Collider> workers_;
  std::vector<Counters> block_counters_;
  /// In a frame: each block's change of the moments sum m u u^T in the pass, added in block order.
  std::vector<std::array<double, 4>> block_moments_;
  void make_workers();
  /// On a worker: block j of `master` over [t_start, t_stop), drawing from the stream (key, j); its
  /// counts go to master.block_counters_[j], its bounds and credit to the master's arrays.
  void run_block(Collider& master, std::size_t j, double t_start, double t_stop, bool first_visit,
                 std::uint64_t key);
  void run_blocks_pass(double t_start, double t_stop);  ///< every block once, on the threads
  /// On a worker: the current block of one species with constant restitution up to t_stop, the
  /// `majorant` process of run_majorant in a loop of its own (header "Blocks", the kernel): raised
  /// bounds are handled inside. Leaves time_, credit_, bound_ and rate_ as run_substep does.
  template <class Rule, bool Track, bool Framed>
  void run_block_one_species(const Rule& rule, double t_stop);
  /// On a worker: the current block of a mixture with constant restitution up to t_stop, the process of
  /// run_majorant (`Lowrank` false) or run_lowrank (true) on the block's slices in a loop of its own
  /// (header "Mixtures in blocks", the kernel): raised bounds are handled inside. Leaves time_, credit_,
  /// bound_ and rate_ as run_substep does. `Two`: `majorant` with two species (their edge and
  /// offsets in locals).
  template <class Rule, bool Track, bool Lowrank, bool Framed, bool Two = false>
  void run_block_mixture(const Rule& rule, double t_stop);
  /// The constants of species pair (k, j) in the mixture block kernel, row-major S x S (at most
  /// block_species_limit species): the rule's projected constants (rules.hpp; the kernels run only a
  /// rule with the projection, SmoothRule) and the pair's slot in the event counts, in one record of
  /// 32 bytes read only for a collision.
  struct PairKernel {
    rules::SmoothRule::Projected constants;  ///< share_a, share_b, loss
    std::uint32_t event;  ///< min(k, j) S + max(k, j): the slot in Counters::pair_events (0 without them)
  };
  std::vector<PairKernel> pair_kernel_;
  /// The acceptance's constants of pair k S + j, read for every candidate (PairKernel only for a
  /// collision): (pi sigma_kj^2 chi_kj)^2, the `majorant` acceptance compared squared, and for `lowrank`
  /// in blocks w_k + w_j, the acceptance |g| / (w_k + w_j) (set_block_lowrank).
  std::vector<double> pair_cross_section2_, pair_limit_;
  std::vector<std::uint32_t> pair_species_;  ///< (k, j) of pair k S + j, 2 per pair
  /// A mixture with `lowrank` in blocks: each block samples its own low-rank A_ik (header "Mixtures in blocks").
  bool lowrank_blocks() const { return scheme_ == Scheme::lowrank && s_ > 1 && !block_first_.empty(); }
  BlockSampler block_sampler_ = BlockSampler::cheaper;
  bool block_lowrank_ = false;  ///< the blocks of this step run the `lowrank` sampler (choose_block_lowrank)
  /// The step's block sampler from the gas's bounds max_speed2_ (header "Mixtures in blocks", "The cheaper
  /// sampler"): the two block_candidate_rate() weighed by lowrank_candidate_cost.
  bool choose_block_lowrank() const;
  /// sum_ik pi sigma_ik^2 chi_ik w_i N_i N_k n/(N - 1) over the gas's species (w_i = sqrt(max_speed2[i])):
  /// the blocks' `lowrank` candidate rate summed over the blocks, to within the slices' rounding.
  double lowrank_block_rate(const double* max_speed2) const;
  void set_block_lowrank(double n);  ///< on a worker: the current block's A_ik, their alias table and R
  std::vector<double> pair_weights_;   ///< a block's A_ik, S x S (set_block_lowrank)
  segment_tree::AliasTable pair_alias_;  ///< over the S^2 pairs (run_lowrank in a block: viscoelastic)
  /// The mixture kernel's draw of a `lowrank` candidate from one 64-bit word (header "Mixtures in blocks"):
  /// an alias table over 2^m >= max(P^2, 2) cells (the pairs, then zero weights), the cell from the top m
  /// bits, its coin from the next 16 - m, two 24-bit halves for the particles (Lemire, exact by rejection).
  struct LowrankOutcome {
    std::uint32_t first_i, count_i, first_k, count_k;  ///< the slices of species i and k (system indices)
    std::uint32_t reject_i, reject_k;                  ///< 2^24 mod count: a 24-bit half below it is rejected (2^24: every one, below_pair draws)
    std::uint32_t pair;                                ///< i S + k: the pair's PairKernel (and pair_species_)
  };
  struct LowrankCell {
    double fraction;        ///< t 2^c - whole, t the cell's alias threshold, c = 16 - m coin bits
    std::uint32_t whole;    ///< floor(t 2^c): the coin q keeps the cell if q < whole (q = whole: fraction decides)
    std::uint32_t keep;     ///< the cell's outcome (the pair it stands for)
    std::uint32_t other;    ///< its alias's outcome
  };
  std::vector<LowrankCell> lowrank_cells_;        ///< P cells (set_block_lowrank)
  std::vector<LowrankOutcome> lowrank_outcomes_;  ///< P^2 outcomes, the pairs of the P species present in the block
  unsigned lowrank_cell_bits_ = 0;                ///< m
  double step_start_ = 0.0;
  /// Exact vmax_k^2 of block j's slices, read in order, into out[k].
  void set_block_max_speed2(std::size_t block, double* out);
  /// max_kj pi sigma_kj^2 chi_kj (vmax_k + vmax_j), over the species present in a block when its running
  /// counts `cum` are given (a scattered species may have none there), else over all species
  double mixture_bound(const double* max_speed2, const std::size_t* cum = nullptr) const;
  /// Slices (header "Blocks"): species k's particles of block j are [slice_first_[j S + k], + count),
  /// count = slice_cum_[j (S+1) + k + 1] - slice_cum_[j (S+1) + k]; cum is the block's running count.
  std::vector<std::size_t> slice_first_, slice_cum_;
  /// A species with at least min_slice K particles is dealt round the K blocks in equal slices; a rarer
  /// one is scattered (header "Mixtures in blocks": each particle to a uniformly random block, anew at
  /// every remix).
  static constexpr std::size_t min_slice = 64;
  std::vector<std::uint8_t> scattered_;   ///< per species: 1 if scattered (with blocks)
  bool scattered_any_ = false;
  std::vector<std::size_t> slice_count_;  ///< each block's count of each species, K x S
  void scatter(std::size_t species);      ///< shuffles the species' particles and draws its slice counts
  void set_slices();                      ///< slice_first_, slice_cum_ and block_first_ from slice_count_
  /// With blocks a step is this many majorant mean free times (times step_fraction): each block
  /// is then visited for about one collision per particle, which repays bringing it into the cache.
  static constexpr double block_steps = 5.0;
  /// ... or longer, to block_step_collisions_ collisions per particle (header "Blocks", "Step length"),
  /// which is at most this many (an elastic gas's bounds do not loosen within a step) ...
  static constexpr double block_step_collisions_max = 6.0;
  double block_step_collisions_ = 0.0;  ///< 0: block_steps mean free times (viscoelastic restitution)
  /// ... and of at most this many candidates (3/4 of 2^24, about 0.25 s of work) when longer than
  /// block_steps: the simulation's chunks of 2^24 candidates at the last step's rate then end at its
  /// end, not just before it, even after the rate fell by a quarter from one step to the next.
  static constexpr double max_block_step_candidates = 12582912.0;
  std::size_t range_first_ = 0, range_count_ = 0;
  deal::Workspace remix_workspace_;  ///< remix() deals the particles in place with this (deal.hpp)
  template <class Rule, bool Framed>
  int run_pairs(const Rule& rule, double t_stop, std::uint64_t event_target);
  template <class Rule, bool Framed>
  int run_lowrank(const Rule& rule, double t_stop, std::uint64_t event_target);
  void set_lowrank_row(std::size_t species);
  void count_event(std::uint32_t k, std::uint32_t j);
  /// The general loops' collision of particles a (species k) and b (species j) along e with `g_dot_e`
  /// of the actual velocities: the rule (rules.hpp) on the stored velocities (in a frame along G^-1 e,
  /// the frame's moments following them: header "Frame"), the energy lost added up, the event counted.
  template <class Rule, bool Framed>
  rules::Outcome collide_pair(const Rule& rule, std::size_t a, std::size_t b, std::uint32_t k, std::uint32_t j,
                              double ex, double ey, double ez, double g_dot_e) {
    rules::Contact contact{ex, ey, ez, g_dot_e, ex, ey, ez};
    particles::Vec3& ua = sys_.v[a];
    particles::Vec3& ub = sys_.v[b];
    rules::Outcome out;
    if constexpr (Framed) {
      const particles::Vec3 w = to_stored(ex, ey, ez);  // G^-1 e
      contact.dx = w.x, contact.dy = w.y, contact.dz = w.z;
      const double ma = mix_.mass[k], mb = mix_.mass[j];
      // The moments change by m (u'u'^T - u u^T) for each partner.
      add_moments(moments_, ua, -ma);
      add_moments(moments_, ub, -mb);
      out = rule.collide(ua, ub, rule.pair(k, j), contact);
      add_moments(moments_, ua, ma);
      add_moments(moments_, ub, mb);
    } else {
      out = rule.collide(ua, ub, rule.pair(k, j), contact);
    }
    counters_.dissipated += out.loss;
    count_event(k, j);
    return out;
  }
  /// The actual relative velocity G g of a stored one (header, "Frame"); the identity without a frame.
  template <bool Framed>
  void to_actual(double& gx, double& gy, double& gz) const {
    if constexpr (Framed) {
      gx = frame_scale_ * (gx + frame_shear_ * gy);
      gy *= frame_scale_;
      gz *= frame_scale_;
    }
  }
  /// G^-1 w of an actual vector w (header, "Frame"): the change of the stored u for an impulse along w.
  particles::Vec3 to_stored(double wx, double wy, double wz) const {
    return {(wx - frame_shear_ * wy) * frame_inverse_scale_, wy * frame_inverse_scale_, wz * frame_inverse_scale_};
  }
  /// q += w u u^T in the frame's four moments (xx, yy, zz, xy).
  static void add_moments(std::array<double, 4>& q, const particles::Vec3& u, double w) {
    q[0] += w * u.x * u.x, q[1] += w * u.y * u.y, q[2] += w * u.z * u.z;
    q[3] += w * u.x * u.y;
  }

  /// An acceptance probability `p` > 1 (header of Counters::overshoots); kept out of line, it never
  /// happens in a correct run.
  [[gnu::cold]] void note_overshoot(double p) {
    ++counters_.overshoots;
    counters_.largest_acceptance = std::max(counters_.largest_acceptance, p);
  }

  /// A candidate drawn ahead: particles a and b, of species i and k (lowrank; 0 otherwise).
  struct PendingPair {
    std::uint32_t a, b, i, k;
  };
  static constexpr std::size_t lookahead = 8;  ///< candidates drawn ahead (header, "Look-ahead")
  /// The same in the block kernels: more in a frame, whose stages leave the blocks out of the caches (header "Look-ahead").
  template <bool Framed>
  static constexpr std::size_t block_lookahead = Framed ? 32 : 8;
  void prefetch(const PendingPair& p) const;
  /// The oldest drawn-ahead candidate; `draw()` replaces it at the end of the queue.
  template <class Draw>
  PendingPair next_pair(Draw&& draw);
  std::array<PendingPair, lookahead> pending_{};
  std::size_t pending_next_ = 0;
  bool pending_filled_ = false;

  Scheme scheme_;
  const species::Mixture& mix_;
  particles::System& sys_;
  rng::Xoshiro256pp gen_;
  double step_fraction_;
  std::size_t s_;
  bool tables_;  ///< pair constants stored as S x S tables (all but lowrank with very many species)
  std::vector<double> cross_section_;   ///< pi sigma_kj^2 chi_kj, row-major S x S
  rules::Rule rule_;                    ///< what a collision does (rules.hpp)
  /// The rule has the projection option (rules.hpp), which the block kernels need; without it
  /// (viscoelastic) the blocks run the general loops.
  bool kernels_ = true;
  std::vector<double> max_speed_;       ///< vmax_k
  std::vector<double> max_speed2_;      ///< vmax_k^2
  std::vector<std::size_t> raised_;     ///< species whose vmax was raised since the last rebuild
  segment_tree::LowRankSampler<3> lowrank_;  ///< A_ik (lowrank)
  double chi_max_ = 1.0;                ///< max_ik chi_ik (lowrank)
  double shear_rate_ = 0.0;             ///< a of set_shear (pairs, Enskog)
  std::vector<double> contact_;         ///< sigma_ij (set_shear)
  double lowrank_volume_ = 0.0;         ///< V = (N - 1)/n (lowrank)
  bool framed_ = false;                 ///< velocities stored in a frame (set_frame)
  double frame_scale_ = 1.0, frame_shear_ = 0.0;  ///< S and c of the frame
  double frame_inverse_scale_ = 1.0;    ///< 1/S, set with S (to_stored needs no division per collision)
  double speed_factor_ = 1.0;           ///< ||G|| (frame_norm), 1 without a frame: every bound's factor
  std::array<double, 4> moments_{};     ///< sum m u u^T: xx, yy, zz, xy (in a frame)
  bool lowrank_columns_set_ = false;    ///< columns v_k set and frozen (they never change in a run)
  // Bounds.
  double bound_ = 0.0;                  ///< B (majorant)
  std::vector<double> pair_rate_;       ///< R_ij (pairs), cumulative in pair_cumulative_
  std::vector<double> pair_cumulative_;
  double rate_ = 0.0;                   ///< total candidate rate R
  double time_ = 0.0;
  double credit_ = 0.0;          ///< time since the last candidate, carried between sub-steps
  double next_step_time_ = 0.0;  ///< when the bounds are next recomputed
  Counters counters_;
};

Scheme parse_scheme(const std::string& name);  ///< throws std::invalid_argument

}  // namespace gdsmc::collide
