/* SPDX-License-Identifier: MIT */
/* bf_he_series.h -- a data pass's series D (Eq. 78) summed around its
 * peak (bf_he_series_x), with the partials of its log, and the rough-surface
 * limit in logs (bf_he_pass.h: the numerics; bf_he_model.h: the model). */
#ifndef BF_HE_SERIES_H
#define BF_HE_SERIES_H

#ifndef __OPENCL_VERSION__
#include "bf_he_surface.h"
#endif

/* bf_he_rcp[k] = 1 / k for k = 1..BF_HE_MMAX (entry 0 is 0), as 1.0 / k
 * gives it (correctly rounded): bf_he_series_x's terms take 1 / k from it,
 * to the bit what they divided for (a division a term, on the loop's
 * critical path: a stride-subset pass at brass's fit, the rows' series, 4%
 * faster). */
BF_HE_CONSTANT double bf_he_rcp[BF_HE_MMAX + 1] = {
    0.0, 1.0, 0.5, 0.3333333333333333,
    0.25, 0.2, 0.16666666666666666, 0.14285714285714285,
    0.125, 0.1111111111111111, 0.1, 0.09090909090909091,
    0.08333333333333333, 0.07692307692307693, 0.07142857142857142, 0.06666666666666667,
    0.0625, 0.058823529411764705, 0.05555555555555555, 0.05263157894736842,
    0.05, 0.047619047619047616, 0.045454545454545456, 0.043478260869565216,
    0.041666666666666664, 0.04, 0.038461538461538464, 0.037037037037037035,
    0.03571428571428571, 0.034482758620689655, 0.03333333333333333, 0.03225806451612903,
    0.03125, 0.030303030303030304, 0.029411764705882353, 0.02857142857142857,
    0.027777777777777776, 0.02702702702702703, 0.02631578947368421, 0.02564102564102564,
    0.025, 0.024390243902439025, 0.023809523809523808, 0.023255813953488372,
    0.022727272727272728, 0.022222222222222223, 0.021739130434782608, 0.02127659574468085,
    0.020833333333333332, 0.02040816326530612, 0.02, 0.0196078431372549,
    0.019230769230769232, 0.018867924528301886, 0.018518518518518517, 0.01818181818181818,
    0.017857142857142856, 0.017543859649122806, 0.017241379310344827, 0.01694915254237288,
    0.016666666666666666, 0.01639344262295082, 0.016129032258064516, 0.015873015873015872,
    0.015625, 0.015384615384615385, 0.015151515151515152, 0.014925373134328358,
    0.014705882352941176, 0.014492753623188406, 0.014285714285714285, 0.014084507042253521,
    0.013888888888888888, 0.0136986301369863, 0.013513513513513514, 0.013333333333333334,
    0.013157894736842105, 0.012987012987012988, 0.01282051282051282, 0.012658227848101266,
    0.0125, 0.012345679012345678, 0.012195121951219513, 0.012048192771084338,
    0.011904761904761904, 0.011764705882352941, 0.011627906976744186, 0.011494252873563218,
    0.011363636363636364, 0.011235955056179775, 0.011111111111111112, 0.01098901098901099,
    0.010869565217391304, 0.010752688172043012, 0.010638297872340425, 0.010526315789473684,
    0.010416666666666666, 0.010309278350515464, 0.01020408163265306, 0.010101010101010102,
    0.01, 0.009900990099009901, 0.00980392156862745, 0.009708737864077669,
    0.009615384615384616, 0.009523809523809525, 0.009433962264150943, 0.009345794392523364,
    0.009259259259259259, 0.009174311926605505, 0.00909090909090909, 0.009009009009009009,
    0.008928571428571428, 0.008849557522123894, 0.008771929824561403, 0.008695652173913044,
    0.008620689655172414, 0.008547008547008548, 0.00847457627118644, 0.008403361344537815,
    0.008333333333333333, 0.008264462809917356, 0.00819672131147541, 0.008130081300813009,
    0.008064516129032258, 0.008, 0.007936507936507936, 0.007874015748031496,
    0.0078125, 0.007751937984496124, 0.007692307692307693, 0.007633587786259542,
    0.007575757575757576, 0.007518796992481203, 0.007462686567164179, 0.007407407407407408,
    0.007352941176470588, 0.0072992700729927005, 0.007246376811594203, 0.007194244604316547,
    0.007142857142857143, 0.0070921985815602835, 0.007042253521126761, 0.006993006993006993,
    0.006944444444444444, 0.006896551724137931, 0.00684931506849315, 0.006802721088435374,
    0.006756756756756757, 0.006711409395973154, 0.006666666666666667, 0.006622516556291391,
    0.006578947368421052, 0.006535947712418301, 0.006493506493506494, 0.0064516129032258064,
    0.00641025641025641, 0.006369426751592357, 0.006329113924050633, 0.006289308176100629,
    0.00625, 0.006211180124223602, 0.006172839506172839, 0.006134969325153374,
    0.006097560975609756, 0.006060606060606061, 0.006024096385542169, 0.005988023952095809,
    0.005952380952380952, 0.005917159763313609, 0.0058823529411764705, 0.005847953216374269,
    0.005813953488372093, 0.005780346820809248, 0.005747126436781609, 0.005714285714285714,
    0.005681818181818182, 0.005649717514124294, 0.0056179775280898875, 0.00558659217877095,
    0.005555555555555556, 0.0055248618784530384, 0.005494505494505495, 0.00546448087431694,
    0.005434782608695652, 0.005405405405405406, 0.005376344086021506, 0.0053475935828877,
    0.005319148936170213, 0.005291005291005291, 0.005263157894736842, 0.005235602094240838,
    0.005208333333333333, 0.0051813471502590676, 0.005154639175257732, 0.005128205128205128,
    0.00510204081632653, 0.005076142131979695, 0.005050505050505051, 0.005025125628140704,
    0.005, 0.004975124378109453, 0.0049504950495049506, 0.0049261083743842365,
    0.004901960784313725, 0.004878048780487805, 0.0048543689320388345, 0.004830917874396135,
    0.004807692307692308, 0.004784688995215311, 0.004761904761904762, 0.004739336492890996,
    0.0047169811320754715, 0.004694835680751174, 0.004672897196261682, 0.004651162790697674,
    0.004629629629629629, 0.004608294930875576, 0.0045871559633027525, 0.0045662100456621,
    0.004545454545454545, 0.004524886877828055, 0.0045045045045045045, 0.004484304932735426,
    0.004464285714285714, 0.0044444444444444444, 0.004424778761061947, 0.004405286343612335,
    0.0043859649122807015, 0.004366812227074236, 0.004347826086956522, 0.004329004329004329,
    0.004310344827586207, 0.004291845493562232, 0.004273504273504274, 0.00425531914893617,
    0.00423728813559322, 0.004219409282700422, 0.004201680672268907, 0.0041841004184100415,
    0.004166666666666667, 0.004149377593360996, 0.004132231404958678, 0.00411522633744856,
    0.004098360655737705, 0.004081632653061225, 0.0040650406504065045, 0.004048582995951417,
    0.004032258064516129, 0.004016064257028112, 0.004, 0.00398406374501992,
    0.003968253968253968, 0.003952569169960474, 0.003937007874015748, 0.00392156862745098,
    0.00390625, 0.0038910505836575876, 0.003875968992248062, 0.003861003861003861,
    0.0038461538461538464, 0.0038314176245210726, 0.003816793893129771, 0.0038022813688212928,
    0.003787878787878788, 0.0037735849056603774, 0.0037593984962406013, 0.003745318352059925,
    0.0037313432835820895, 0.0037174721189591076, 0.003703703703703704, 0.0036900369003690036,
    0.003676470588235294, 0.003663003663003663, 0.0036496350364963502, 0.0036363636363636364,
    0.0036231884057971015, 0.0036101083032490976, 0.0035971223021582736, 0.0035842293906810036,
    0.0035714285714285713, 0.0035587188612099642, 0.0035460992907801418, 0.0035335689045936395,
    0.0035211267605633804, 0.0035087719298245615, 0.0034965034965034965, 0.003484320557491289,
    0.003472222222222222, 0.0034602076124567475, 0.0034482758620689655, 0.003436426116838488,
    0.003424657534246575, 0.0034129692832764505, 0.003401360544217687, 0.003389830508474576,
    0.0033783783783783786, 0.003367003367003367, 0.003355704697986577, 0.0033444816053511705,
    0.0033333333333333335, 0.0033222591362126247, 0.0033112582781456954, 0.0033003300330033004,
    0.003289473684210526, 0.003278688524590164, 0.0032679738562091504, 0.003257328990228013,
    0.003246753246753247, 0.003236245954692557, 0.0032258064516129032, 0.003215434083601286,
    0.003205128205128205, 0.003194888178913738, 0.0031847133757961785, 0.0031746031746031746,
    0.0031645569620253164, 0.0031545741324921135, 0.0031446540880503146, 0.003134796238244514,
    0.003125, 0.003115264797507788, 0.003105590062111801, 0.0030959752321981426,
    0.0030864197530864196, 0.003076923076923077, 0.003067484662576687, 0.0030581039755351682,
    0.003048780487804878, 0.00303951367781155, 0.0030303030303030303, 0.0030211480362537764,
    0.0030120481927710845, 0.003003003003003003, 0.0029940119760479044, 0.0029850746268656717,
    0.002976190476190476, 0.002967359050445104, 0.0029585798816568047, 0.0029498525073746312,
    0.0029411764705882353, 0.002932551319648094, 0.0029239766081871343, 0.0029154518950437317,
    0.0029069767441860465, 0.002898550724637681, 0.002890173410404624, 0.002881844380403458,
    0.0028735632183908046, 0.0028653295128939827, 0.002857142857142857, 0.002849002849002849,
    0.002840909090909091, 0.0028328611898017, 0.002824858757062147, 0.0028169014084507044,
    0.0028089887640449437, 0.0028011204481792717, 0.002793296089385475, 0.002785515320334262,
    0.002777777777777778, 0.002770083102493075, 0.0027624309392265192, 0.0027548209366391185,
    0.0027472527472527475, 0.0027397260273972603, 0.00273224043715847, 0.0027247956403269754,
    0.002717391304347826, 0.0027100271002710027, 0.002702702702702703, 0.0026954177897574125,
    0.002688172043010753, 0.002680965147453083, 0.00267379679144385, 0.0026666666666666666,
    0.0026595744680851063, 0.002652519893899204, 0.0026455026455026454, 0.002638522427440633,
    0.002631578947368421, 0.0026246719160104987, 0.002617801047120419, 0.0026109660574412533,
    0.0026041666666666665, 0.0025974025974025974, 0.0025906735751295338, 0.002583979328165375,
    0.002577319587628866, 0.002570694087403599, 0.002564102564102564, 0.0025575447570332483,
    0.002551020408163265, 0.002544529262086514, 0.0025380710659898475, 0.002531645569620253,
    0.0025252525252525255, 0.0025188916876574307, 0.002512562814070352, 0.002506265664160401,
    0.0025
};

/* d(m) = ln(T_{m+1} / T_m), T_m = g^m e^-g / (m! m) e^(-a/m): decreasing in m,
 * for whole m in [1, BF_HE_MMAX - 1] (larger m read as BF_HE_MMAX - 1).
 * ln((m + 1)^2 / m) is bf_he_lkk[m + 1] - bf_he_lkk[m], to ~5e-13 absolute
 * (the table's rounding at ~2000): a lane's two logarithms would be most of
 * a peak search.  So the sign is exact but where two terms tie to within
 * e^(5e-13) (either is then a peak: the sums agree to rounding). */
BF_FN BF_REAL bf_he_dlog(BF_REAL m, BF_REAL lng, BF_REAL a)
{
    BF_REAL mc = fmin(m, BF_R(BF_HE_MMAX - 1));
    BF_REAL l0 = BF_GATHERC(bf_he_lkk, mc), l1 = BF_GATHERC(bf_he_lkk, mc + 1.0);
    return lng - (l1 - l0) + a / (m * (m + 1.0));
}

/* The discrete peak m* of the terms T_m of bf_he_series_x for the lanes
 * where act > 0: d(m* - 1) > 0 >= d(m*) (or m* = 1, = BF_HE_MMAX), found
 * from the continuous peak of ln T_m ~ m ln(g/m) + m - a/m, ln(m/g) = a/m^2
 * (one Newton step in y = ln m from a first guess y0, where a e^(-2 y0) is
 * known without an exp: the guess is ln g or (ln a - ln L) / 2, or a clamp
 * of either), then by single steps:
 * over g in [1e-6, 19] and a in [0, 1e7] (a grid of 401 x 401) at most 3 of
 * them, 0.21 on average (three Newton steps left 0.17, each an exp a lane:
 * a stride-subset pass at brass's fit 5% faster with one, the peak and so
 * every sum the same).  *conv = 0 in a lane whose steps hit their cap (it is
 * then summed in full), else 1. */
BF_FN_INLINE BF_REAL bf_he_series_peak(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL la, BF_REAL act,
                                       BF_REAL *conv)
{
    const double mmax = (double)BF_HE_MMAX, lnmmax = BF_HE_LN_MMAX;
    BF_REAL L = fmax(0.5 * la - lng, BF_R(1.0));
    BF_REAL yb = 0.5 * (la - log(L));
    BF_REAL y = fmax(lng, yb);
    /* e = a e^(-2y): L where y = yb (la = ln a to rounding, and la only
     * places the start), a / g^2 where y = ln g, a and a / mmax^2 at the clamps */
    BF_REAL e = BF_SEL(a / (g * g), L, yb > lng);
    e = BF_SEL(e, a, y < 0.0);
    e = BF_SEL(e, a * (1.0 / (mmax * mmax)), y > lnmmax);
    y = fmin(fmax(y, 0.0), lnmmax);
    y = fmin(fmax(y - (y - lng - e) / (1.0 + 2.0 * e), 0.0), lnmmax);
    BF_REAL m = fmin(fmax(floor(exp(y) + 0.5), BF_R(1.0)), BF_R(mmax));

    BF_REAL up = BF_SEL(BF_R(0.0), BF_R(1.0),
                        (act > 0.0) && (m < mmax) && (bf_he_dlog(m, lng, a) > 0.0));
    for (int it = 0; it < 64 && BF_ANY(up > 0.0); it++) {
        m = BF_SEL(m, m + 1.0, up > 0.0);
        up = BF_SEL(BF_R(0.0), BF_R(1.0),
                    (act > 0.0) && (m < mmax) && (bf_he_dlog(m, lng, a) > 0.0));
    }
    BF_REAL dn = BF_SEL(BF_R(0.0), BF_R(1.0),
                        (act > 0.0) && (m > 1.0)
                            && (bf_he_dlog(fmax(m - 1.0, BF_R(1.0)), lng, a) <= 0.0));
    for (int it = 0; it < 64 && BF_ANY(dn > 0.0); it++) {
        m = BF_SEL(m, m - 1.0, dn > 0.0);
        dn = BF_SEL(BF_R(0.0), BF_R(1.0),
                    (act > 0.0) && (m > 1.0)
                        && (bf_he_dlog(fmax(m - 1.0, BF_R(1.0)), lng, a) <= 0.0));
    }
    *conv = BF_SEL(BF_R(1.0), BF_R(0.0), (up > 0.0) || (dn > 0.0));
    return m;
}

/* The first m (a scalar for the vector) from which bf_he_series_x sums
 * the lanes where act > 0: at most each lane's first term within e^-drop of
 * its peak term m (conv: m is the peak; else from 1), drop = min(BF_HE_HEAD, the
 * peak's height above the floor: bf_he_series_x).  The curvature of ln T is
 * at least kap on [3, m], so ln T(m - w) <= ln T(m) - kap w (w - 1) / 2. */
BF_FN_INLINE int bf_he_series_first(BF_REAL m, BF_REAL a, BF_REAL conv, BF_REAL act,
                                    BF_REAL drop)
{
    BF_REAL x1 = m + 1.0;
    BF_REAL kap = 2.0 * a / (x1 * x1 * x1) + (m - 1.0) / (m * x1);
    BF_REAL w = 0.5 + sqrt(0.25 + (2.0 * drop) / fmax(kap, BF_R(1e-300)));
    BF_REAL mlo = floor(m - w);
    mlo = BF_SEL(mlo, BF_R(1.0), (mlo < 3.0) || (conv <= 0.0));
    mlo = BF_SEL(BF_R(1e9), mlo, act > 0.0);
    int m0 = 1;
    while (m0 + 16 <= BF_HE_MMAX && !BF_ANY(mlo <= (double)(m0 + 16)))
        m0 += 16;
    while (m0 < BF_HE_MMAX && !BF_ANY(mlo <= (double)m0))
        m0++;
    return m0;
}

/* sum_{m>=1} exp(ln T_m + lk) for the lanes where act > 0 (the others: 0),
 * for g = min(g, 19) > 0 with lng = ln g, a >= 0 with la ~ ln a (only a
 * starting point depends on la).  See bf_he_pass.h's header comment; a lane whose peak
 * term puts less than e^ldead into the value (lpk + lk < ldead) is dead: 0,
 * not summed.  ldead is BF_HE_LN_DEAD (where the value underflows) but in a
 * pass's bin rows (bf_he_row_floor), where a live lane's sum also leaves out
 * the terms below e^ldead at either end: it starts within e^-drop of the
 * peak, drop the smaller of BF_HE_HEAD and the peak's height above the
 * floor, and stops at the first term below the floor past the peak (with
 * BF_HE_LN_DEAD, what it so leaves out of K lies below the smallest
 * subnormal, e^-744).
 *
 * With deriv != 0 (a constant at every call) it also returns the partials of
 * ln V, V = e^(lpk + lk) sum_m t_m (t_m = T_m / T_m*, the terms it sums):
 *     *vg = d ln V / dg = sum m t_m / (g sum t_m) - 1
 *     *va = d ln V / da = -sum (t_m / m) / sum t_m
 * (of the truncated sum, from the same terms: no further exp; 0 where V is
 * 0), and the two factors of V: *lpko = lpk (of every lane active on entry
 * whose peak was sought) and *sumo = sum t_m (0 where the lane was not
 * summed: inactive, or dead, lpk + lk < ldead).  The value is the same, bit for bit, with and
 * without them. */
BF_FN BF_REAL bf_he_series_x(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL la, BF_REAL lk,
                             double ldead, BF_REAL act, int deriv, BF_REAL *vg, BF_REAL *va,
                             BF_REAL *lpko, BF_REAL *sumo)
{
    if (deriv) {
        *vg = BF_R(0.0);
        *va = BF_R(0.0);
        *lpko = BF_R(0.0);
        *sumo = BF_R(0.0);
    }
    if (!BF_ANY(act > 0.0))
        return BF_R(0.0);
    BF_REAL conv;
    BF_REAL m = bf_he_series_peak(g, lng, a, la, act, &conv);

    /* ln T at the peak (ln(m m!) from the table): too small -> 0. */
    BF_REAL lpk = m * lng - BF_GATHERC(bf_he_lkk, m) - g - a / m;
    act = BF_SEL(act, BF_R(0.0), (conv > 0.0) && (lpk + lk < ldead));
    if (deriv)
        *lpko = lpk;
    if (!BF_ANY(act > 0.0))
        return BF_R(0.0);

    /* The sum, while some lane is before its peak or above 1e-12 of its sum,
     * of the terms relative to the peak (exp's arguments stay in about
     * [-60, 0], away from its slow underflow paths; the clamps only guard
     * the finiteness of lanes that are not summed). */
    BF_REAL sum = BF_R(0.0), s1 = BF_R(0.0), sinv = BF_R(0.0);
    BF_REAL base = -g - lpk;
    BF_REAL fl = BF_R(ldead) - (lpk + lk); /* the floor, relative to the peak term */
    BF_REAL drop = fmin(BF_R(BF_HE_HEAD), fmax(-fl, BF_R(0.0)));
    for (int k = bf_he_series_first(m, a, conv, act, drop); k <= BF_HE_MMAX; k++) {
        double dk = (double)k, ik = bf_he_rcp[k];
        BF_REAL e = dk * lng - a * ik + (base - bf_he_lkk[k]);
        BF_REAL t = bf_exp(fmin(fmax(e, BF_R(-700.0)), BF_R(700.0)));
        /* a term below the floor is left out wherever the lane's vector
         * starts (before the peak) and ends the lane (past it) */
        sum = BF_SEL(sum, sum + t, (act > 0.0) && (e >= fl));
        if (deriv) {
            s1 = BF_SEL(s1, s1 + t * dk, (act > 0.0) && (e >= fl));
            sinv = BF_SEL(sinv, sinv + t * ik, (act > 0.0) && (e >= fl));
        }
        act = BF_SEL(act, BF_R(0.0), (m <= dk) && ((t <= 1e-12 * sum) || (e < fl)));
        if (!BF_ANY(act > 0.0))
            break;
    }
    BF_REAL sc = exp(fmin(lpk + lk, BF_R(700.0)));
    if (deriv) {
        /* sum >= 1 where a lane was summed (its peak term is 1) */
        BF_REAL is = BF_SEL(BF_R(0.0), 1.0 / fmax(sum, BF_R(1.0)), sum > 0.0);
        *vg = (s1 * is) / g - BF_SEL(BF_R(0.0), BF_R(1.0), sum > 0.0);
        *va = -(sinv * is);
        *sumo = sum;
    }
    return sum * sc;
}

/* The rough limit e^(lk - a/g) / g (g clamped to >= 18) of the scaled
 * series (bf_he_D_limit in bf_he_model.h, in logs). */
BF_FN BF_REAL bf_he_limit(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL lk)
{
    return exp(lk - a / fmax(g, BF_HE_G_LO) - fmax(lng, BF_R(BF_HE_LN_G_LO)));
}

#endif /* BF_HE_SERIES_H */
