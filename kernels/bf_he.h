/* SPDX-License-Identifier: MIT */
/*
 * bf_he.h -- the He et al. 1991 directional-diffuse lobe as Ngan et al. fitted
 * it: p0 = tau (autocorrelation length, um), p1 = sigma0 (rms roughness, um),
 * p2 = n (real refractive index), K per channel at wavelengths lam[0..2] (um).
 * Written once for the C library and the OpenCL kernel (see bf_common.h).
 *
 * With wi toward the light, wo toward the viewer, v = wi + wo, N = z:
 *
 *   K = F G S D / (pi cos ti cos to)
 *   F  Fresnel, unpolarised, real n, at c = cos theta_b = |v| / 2
 *   G  = (v.v / v_z)^2.  He et al.'s vector form
 *        (v.v / v_z)^2 [(s_r.k_i)^2 + (p_r.k_i)^2] [(s_i.k_r)^2 + (p_i.k_r)^2] / |k_r x k_i|^4
 *      is exactly this: (s_r, p_r, k_r) is an orthonormal basis, so
 *      (s_r.k_i)^2 + (p_r.k_i)^2 = 1 - (k_r.k_i)^2 = |k_r x k_i|^2, and likewise
 *      for the other bracket.  The closed form has no 0/0 at wi = wo (where it
 *      is 4 / cos^2 theta) nor at normal incidence (where s is arbitrary).
 *   S  = S(ti) S(to), S(t) = (1 - erfc(u)/2) / (1 + L(u)), u = tau cot t / (2 sigma0),
 *      L(u) = (exp(-u^2) / (sqrt(pi) u) - erfc(u)) / 2
 *   sigma = sigma0 / sqrt(1 + x^2),  x e^(x^2/2) = (K(ti) + K(to)) / sqrt(8 pi),
 *      K(t) = tan t erfc(u)
 *   g  = ((2 pi sigma / lam)(cos ti + cos to))^2,  a = pi^2 (tau/lam)^2 |v_xy|^2
 *   D  = (pi tau / (2 lam))^2 sum_{m>=1} g^m e^-g / (m! m) e^(-a/m)   (g <= 18)
 *      ~ (pi tau / (2 lam))^2 e^(-a/g) / g                             (g >= 19)
 *      blended linearly in g over [18, 19].
 *
 * Numerics.  The terms T_m of the series are log-concave in m (their log
 * ratios decrease), so per lane the peak m* is found exactly (a Newton
 * estimate, then a step or two on the sign of the log ratio).  K is computed
 * as e^(ln T_m* + ln(pref F G S / (pi cos cos))) sum_m T_m / T_m*, so nothing
 * underflows unless K does: a lane whose peak term puts less than e^-760 into
 * K is 0 without summing (in a pass's bin rows, a higher floor:
 * bf_he_row_floor); the sum starts where the terms are within e^-40 of
 * the peak and stops, past the peak, once a term is below 1e-12 of the sum
 * (relative error ~1e-12; 3e-13 measured against 40-digit sums).  The cap
 * m <= BF_HE_MMAX = 400 is exact: for g < 19, T_m < Poisson(m; 19) < e^-840
 * beyond it, and the scale factor is below e^45 for directions up to 89.9 deg
 * (and far beyond), so no later term reaches the double range.  The peak can
 * lie far beyond the ~80 terms a = 0 needs (m* = 166 at g = 16.3, a = 6.4e4,
 * K = 2e-269: a row of he-reference.tsv).  Cosines are floored at 1e-100, so
 * every lane stays finite for any direction strictly above the horizon.  A
 * data pass takes the series of most lanes from a table of its terms made
 * once per (theta_h, theta_d) bin (bf_he_tab), to the same accuracy.
 */
#ifndef BF_HE_H
#define BF_HE_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#endif

#define BF_HE_G_LO 18.0      /* below: the series                  */
#define BF_HE_G_HI 19.0      /* above: the rough-surface limit      */
#define BF_HE_MMAX 400       /* last term of the series             */
#define BF_HE_COS_MIN 1e-100 /* floor of cos ti, cos to, cos theta_b */
#define BF_HE_LN_DEAD (-760.0) /* a lane below e^this is 0 (the rows: bf_he_row_floor) */
#define BF_HE_U_FLAT 6.0     /* u >= 6: erfc(u) and e^(-u^2) taken as 0 */
#define BF_HE_LN_SQRT_2PI 0.91893853320467274178
/* ln 18, ln 19, ln 400 (BF_HE_G_LO, BF_HE_G_HI, BF_HE_MMAX), correctly rounded:
 * written out, as the kernel compiler does not fold log() of a constant */
#define BF_HE_LN_G_LO 2.8903717578961645
#define BF_HE_LN_G_HI 2.9444389791664403
#define BF_HE_LN_MMAX 5.991464547107982

/* bf_he_lkk[k] = ln(k k!) for k = 1..BF_HE_MMAX, correctly rounded (so that
 * a term of the series costs one exp and no log). */
#ifdef __OPENCL_VERSION__
#define BF_HE_CONSTANT __constant
#else
#define BF_HE_CONSTANT static const
#endif
BF_HE_CONSTANT double bf_he_lkk[BF_HE_MMAX + 1] = {
    0.0, 0.0, 1.3862943611198906, 2.8903717578961645,
    4.564348191467836, 6.396929655216146, 8.371010681238156, 10.471071510120728,
    12.684044444425085, 14.999052057417689, 17.40699766606956, 19.900203118672255,
    22.472121145449886, 25.11711321058496, 27.83027851235394, 30.6073215849431,
    33.44444882832045, 36.3382867941931, 39.28581696592922, 42.28432316636594,
    45.331348734307475, 48.42466133620033, 51.56222380519354, 54.74216978369353,
    57.96278322846027, 61.22248104784872, 64.51979829902348, 67.85337549301066,
    71.22194764735674, 74.62433479715449, 78.05943373049232, 81.52621075780046,
    85.02369535891476, 88.550974579048, 92.10718806681383, 95.6915236651765,
    99.30321348059931, 102.94153036743165, 106.60578477424019, 110.29532190677311,
    114.00951916887134, 117.74778384816601, 121.50955101802845, 125.2942816311322,
    129.10146078327514, 132.93059612889755, 136.7812164321054, 140.65287023903642,
    144.54512465914215, 148.4575642444555, 152.38978995720117, 156.34141821722167,
    160.31208002166022, 164.30142013018303, 168.30909630975947, 172.33477863366014,
    176.37814882989795, 180.4388996748319, 184.5167344280902, 188.6113663053552,
    192.7225179858937, 196.84992115201823, 200.9933160579351, 205.15245112567305,
    209.32708256600088, 213.51697402243246, 217.72189623658969, 221.9416267333452,
    226.17594952430645, 230.42465482832486, 234.68753880782631, 238.96440331985957,
    243.25505568085038, 247.55930844413112, 251.87697918939105, 256.2078903232595,
    260.55186889029585, 264.9087463937169, 269.2783586252424, 273.66054550348684,
    278.05515092036757, 282.4620225950386, 286.8810119348947, 291.3119739032236,
    295.75476689311364, 300.20925260725096, 304.67529594326766, 309.1527648843233,
    313.64153039462514, 318.1414663196112, 322.6524492905396, 327.174358633243,
    331.70707628082425, 336.25048669008174, 340.8044767614685, 345.36893576239953,
    349.9437552537347, 354.52882901927364, 359.1240529981114, 363.72932521971,
    368.3445457415516, 372.969616589246, 377.6044416989733, 382.24892686214827,
    386.9029796722014, 391.56650947337505, 396.23942731144166, 400.92164588625343,
    405.61307950604, 410.31364404337404, 415.0232568927297, 419.741836929562,
    424.4693044708398, 429.2055812369694, 433.95059031504604, 438.70425612337806,
    443.4665043772275, 448.2372620557167, 453.0164573698503, 457.80401973160764,
    462.5998797240602, 467.4039690724717, 472.21622061634145, 477.036568282353,
    481.8649470581907, 486.7012929671902, 491.5455430437909, 496.3976353097566,
    501.25750875113727, 506.12510329594096, 511.0003597924905, 515.8832199884372,
    520.7736265104088, 525.671522844266, 530.576853315946, 535.4895630728719,
    540.4095980659056, 545.3369050318258, 550.271431476312, 555.2131256574163,
    560.1619365695042, 565.1178139276512, 570.0807081524756, 575.0505703553941,
    580.0273523242862, 585.0110065095514, 590.0014860105474, 594.9987445623966,
    600.002736523146, 605.0134168612728, 610.0307411435199, 615.0546655230536,
    620.0851467279311, 625.1221420498698, 630.1656093333046, 635.2155069647295,
    640.2717938623093, 645.3344294657563, 650.403373726462, 655.4785870978754,
    660.5600305261229, 665.647665440858, 670.7414537463383, 675.8413578127195,
    680.947340467561, 686.0593649875381, 691.1773950903505, 696.3013949268275,
    701.4313290732173, 706.5671625236602, 711.7088606828376, 716.8563893587926,
    722.0097147559169, 727.168803468099, 732.3336224720302, 737.5041391206628,
    742.6803211368156, 747.8621366069251, 753.0495539749354, 758.2425420363248,
    763.4410699322646, 768.645107143906, 773.8546234867937, 779.0695891053998,
    784.2899744677763, 789.515750360324, 794.746887882672, 799.9833584426681,
    805.2251337514733, 810.4721858187627, 815.724486948024, 820.9820097319567,
    826.2447270479657, 831.5126120537477, 836.7856381829695, 842.0637791410337,
    847.347008900931, 852.6353016991764, 857.9286320318275, 863.226974650582,
    868.5303045589535, 873.8385970085236, 879.151827495267, 884.4699717559494,
    889.7930057645959, 895.1209057290286, 900.4536480874693, 905.7912095052105,
    911.1335668713477, 916.4806972955761, 921.8325781050462, 927.1891868412808,
    932.5505012571488, 937.9164993138957, 943.2871591782299, 948.6624592194634,
    954.0423780067041, 959.4268943061008, 964.8159870781385, 970.2096354749824,
    975.6078188378707, 981.0105166945538, 986.4177087567806, 991.8293749178285,
    997.2454952500785, 1002.6660500026323, 1008.0910195989725, 1013.5203846346631,
    1018.9541258750905, 1024.3922242532444, 1029.8346608675367, 1035.281416979657,
    1040.732474012468, 1046.187813547933, 1051.6474173250826, 1057.1112672380134,
    1062.5793453339204, 1068.051633811165, 1073.5281150173728, 1079.0087714475644,
    1084.4935857423168, 1089.982540685956, 1095.475619204779, 1100.9728043653033,
    1106.474079372549, 1111.9794275683455, 1117.4888324296653, 1123.002277566989,
    1128.519746722691, 1134.0412237694554, 1139.5666927087152, 1145.0961376691166,
    1150.6295429050076, 1156.1668927949513, 1161.7081718402608, 1167.253364663559,
    1172.8024560073598, 1178.3554307326706, 1183.9122738176186, 1189.472970356096,
    1195.0375055564277, 1200.6058647400575, 1206.1780333402571, 1211.7539969008515,
    1217.3337410749664, 1222.9172516237925, 1228.5045144153696, 1234.0955154233884,
    1239.69024072601, 1245.2886765047026, 1250.8908090430975, 1256.4966247258587,
    1262.106110037571, 1267.7192515616448, 1273.336035979236, 1278.956450068181,
    1284.5804807019488, 1290.2081148486063, 1295.8393395698004, 1301.4741420197524,
    1307.1125094442696, 1312.7544291797678, 1318.3998886523102, 1324.0488753766585,
    1329.7013769553378, 1335.3573810777139, 1341.016875519085, 1346.6798481397843,
    1352.3462868842967, 1358.0161797803855, 1363.6895149382342, 1369.3662805495965,
    1375.0464648869618, 1380.7300563027275, 1386.417043228388, 1392.1074141737288,
    1397.801157726037, 1403.4982625493185, 1409.1987173835264, 1414.9025110438024,
    1420.6096324197242, 1426.3200704745657, 1432.0338142445667, 1437.7508528382104,
    1443.4711754355135, 1449.194771287322, 1454.9216297146195, 1460.6517401078415,
    1466.3850919262015, 1472.1216746970233, 1477.861478015084, 1483.6044915419634,
    1489.350705005403, 1495.1001081986738, 1500.8526909799502, 1506.6084432716932,
    1512.3673550600415, 1518.129416394209, 1523.8946173858922, 1529.6629482086817,
    1535.4343990974844, 1541.2089603479506, 1546.9866223159095, 1552.7673754168104,
    1558.5512101251722, 1564.3381169740394, 1570.1280865544431, 1575.921109514871,
    1581.717176560742, 1587.5162784538886, 1593.3184060120443, 1599.123550108338,
    1604.9317016707937, 1610.7428516818381, 1616.5569911778111, 1622.3741112484845,
    1628.1942030365858, 1634.0172577373273, 1639.843266597941, 1645.672220917219,
    1651.504112045059, 1657.3389313820157, 1663.1766703788574, 1669.0173205361268,
    1674.8608734037075, 1680.707320580397, 1686.556653713481, 1692.408864498317,
    1698.263944677919, 1704.1218860425495, 1709.9826804293139, 1715.8463197217623,
    1721.7127958494925, 1727.582100787761, 1733.4542265570954, 1739.3291652229123,
    1745.206908895141, 1751.0874497278483, 1756.97077991887, 1762.8568917094458,
    1768.7457773838578, 1774.6374292690734, 1780.5318397343922, 1786.4290011910962,
    1792.3289060921047, 1798.231546931633, 1804.1369162448532, 1810.045006607561,
    1815.9558106358443, 1821.8693209857563, 1827.7855303529925, 1833.704431472569,
    1839.626017118508, 1845.5502801035223, 1851.4772132787075, 1857.4068095332339,
    1863.3390617940433, 1869.2739630255494, 1875.2115062293406, 1881.1516844438859,
    1887.0944907442442, 1893.0399182417773, 1898.9879600838638, 1904.9386094536185,
    1910.8918595696132, 1916.8477036856011, 1922.8061350902428, 1928.7671471068377,
    1934.7307330930544, 1940.696886440668, 1946.665600575297, 1952.636868956144,
    1958.6106850757396, 1964.5870424596876, 1970.5659346664143, 1976.5473552869184,
    1982.5312979445264, 1988.5177562946462, 1994.506724024528, 2000.4981948530233,
    2006.4921625303493
};

/* Fresnel reflectance, unpolarised, real index n >= 1, at c = cos theta_b in
 * (0, 1]; g' - c = (n^2 - 1) / (g' + c) without cancellation for n ~ 1. */
BF_FN BF_REAL bf_he_fresnel(BF_REAL c, double n)
{
    double e = (n - 1.0) * (n + 1.0);
    BF_REAL gpc = sqrt(e + c * c) + c;
    BF_REAL gmc = e / gpc;
    BF_REAL q = gmc / gpc;
    BF_REAL r = (c * gpc - 1.0) / (c * gmc + 1.0);
    return 0.5 * (q * q) * (1.0 + r * r);
}

/* u = tau cot(theta) / (2 sigma0) from cos and sin, kept in [1e-300, 1e10]
 * (u = 1e10 is the normal: every use below is exactly its u -> inf value there). */
BF_FN BF_REAL bf_he_u(BF_REAL c, BF_REAL s, double tau, double sigma0)
{
    BF_REAL u = (tau / (2.0 * sigma0)) * c / fmax(s, 1e-300);
    return fmin(fmax(u, 1e-300), 1e10);
}

/* erfc(u) for u in [0, BF_HE_U_FLAT], given ex = e^(-u^2): W. J. Cody's
 * rational Chebyshev approximations (Math. Comp. 23, 631-637, 1969; the
 * coefficients of netlib's specfun CALERF): 1 - u A(u^2) / B(u^2) on
 * [0, 0.46875], ex C(u) / D(u) on (0.46875, 4], ex (1/sqrt(pi) - z P(z) / Q(z)) / u,
 * z = 1/u^2, above; each piece only when some lane needs it.  Against glibc's
 * erfc over [0, 6] in steps of 1e-6 (tests/test_he.c, erfc_cody): within
 * 2.3e-15 relative up to u = 5 and 4e-15 up to 6 (where erfc < 2e-12: the
 * rounding of u^2 in ex).  It replaced the OpenCL library's erfc, which cost
 * as much as the rest of a rough sample's shadowing. */
BF_HE_CONSTANT double bf_he_cody_a[5] = {
    3.16112374387056560e00, 1.13864154151050156e02, 3.77485237685302021e02,
    3.20937758913846947e03, 1.85777706184603153e-1
};
BF_HE_CONSTANT double bf_he_cody_b[4] = {
    2.36012909523441209e01, 2.44024637934444173e02, 1.28261652607737228e03,
    2.84423683343917062e03
};
BF_HE_CONSTANT double bf_he_cody_c[9] = {
    5.64188496988670089e-1, 8.88314979438837594e00, 6.61191906371416295e01,
    2.98635138197400131e02, 8.81952221241769090e02, 1.71204761263407058e03,
    2.05107837782607147e03, 1.23033935479799725e03, 2.15311535474403846e-8
};
BF_HE_CONSTANT double bf_he_cody_d[8] = {
    1.57449261107098347e01, 1.17693950891312499e02, 5.37181101862009858e02,
    1.62138957456669019e03, 3.29079923573345963e03, 4.36261909014324716e03,
    3.43936767414372164e03, 1.23033935480374942e03
};
BF_HE_CONSTANT double bf_he_cody_p[6] = {
    3.05326634961232344e-1, 3.60344899949804439e-1, 1.25781726111229246e-1,
    1.60837851487422766e-2, 6.58749161529837803e-4, 1.63153871373020978e-2
};
BF_HE_CONSTANT double bf_he_cody_q[5] = {
    2.56852019228982242e00, 1.87295284992346725e00, 5.27905102951428412e-1,
    6.05183413124413191e-2, 2.33520497626869185e-3
};

BF_FN BF_REAL bf_he_erfc_cody(BF_REAL u, BF_REAL ex)
{
    BF_REAL r = BF_R(0.0);
    if (BF_ANY(u <= 0.46875)) {
        BF_REAL z = u * u, n = bf_he_cody_a[4] * z, d = z;
        for (int i = 0; i < 3; i++) {
            n = (n + bf_he_cody_a[i]) * z;
            d = (d + bf_he_cody_b[i]) * z;
        }
        r = BF_SEL(r, 1.0 - u * (n + bf_he_cody_a[3]) / (d + bf_he_cody_b[3]), u <= 0.46875);
    }
    if (BF_ANY((u > 0.46875) && (u <= 4.0))) {
        BF_REAL n = bf_he_cody_c[8] * u, d = u;
        for (int i = 0; i < 7; i++) {
            n = (n + bf_he_cody_c[i]) * u;
            d = (d + bf_he_cody_d[i]) * u;
        }
        r = BF_SEL(r, ex * (n + bf_he_cody_c[7]) / (d + bf_he_cody_d[7]), (u > 0.46875) && (u <= 4.0));
    }
    if (BF_ANY(u > 4.0)) {
        BF_REAL z = 1.0 / fmax(u * u, BF_R(16.0)), n = bf_he_cody_p[5] * z, d = z;
        for (int i = 0; i < 4; i++) {
            n = (n + bf_he_cody_p[i]) * z;
            d = (d + bf_he_cody_q[i]) * z;
        }
        BF_REAL t = z * (n + bf_he_cody_p[4]) / (d + bf_he_cody_q[4]);
        r = BF_SEL(r, ex * (0.56418958354775628695 - t) / fmax(u, BF_R(4.0)), u > 4.0);
    }
    return r;
}

/* erfc(u) and e^(-u^2) of the shadowing, for u in [1e-300, 1e10], as 0 for
 * u >= BF_HE_U_FLAT = 6 (erfc(6) = 2.2e-17, e^-36 = 2.3e-16): there S(t)
 * rounds to 1 and sigma's r gains less than 1e-14 (sigma: relative 1e-14),
 * so the rule changes no value measurably, and a vector with every u >= 6 (a
 * smooth surface away from grazing) skips both. */
BF_FN void bf_he_erfc2(BF_REAL u, BF_REAL *ec, BF_REAL *ex)
{
    *ec = BF_R(0.0);
    *ex = BF_R(0.0);
    if (BF_ANY(u < BF_HE_U_FLAT)) {
        BF_REAL flat = BF_SEL(BF_R(0.0), BF_R(1.0), u >= BF_HE_U_FLAT);
        BF_REAL us = fmin(u, BF_R(BF_HE_U_FLAT));
        BF_REAL e = exp(-us * us);
        *ec = BF_SEL(bf_he_erfc_cody(us, e), BF_R(0.0), flat > 0.0);
        *ex = BF_SEL(e, BF_R(0.0), flat > 0.0);
    }
}

/* One direction's shadowing S(theta) from u, erfc(u) and exp(-u^2). */
BF_FN BF_REAL bf_he_shadow1x(BF_REAL u, BF_REAL ec, BF_REAL ex)
{
    BF_REAL lam = 0.5 * (ex / (BF_SQRT_PI * u) - ec);
    return (1.0 - 0.5 * ec) / (1.0 + lam);
}

/* dS/du of bf_he_shadow1x, finite for u in [1e-300, 1e10]:
 * with L' = -e^(-u^2) / (2 sqrt(pi) u^2) and (1 + L) u = u + (e^(-u^2) / sqrt(pi) - erfc(u) u) / 2,
 * dS/du = e^(-u^2) / sqrt(pi) (u (1 + L) u + (1 - erfc(u) / 2) / 2) / ((1 + L) u)^2. */
BF_FN BF_REAL bf_he_dshadow1(BF_REAL u, BF_REAL ec, BF_REAL ex)
{
    BF_REAL xs = ex * (1.0 / BF_SQRT_PI);
    BF_REAL lu = u + 0.5 * (xs - ec * u);
    return xs * (u * lu + 0.5 * (1.0 - 0.5 * ec)) / (lu * lu);
}



/* The effective roughness sigma = sigma0 / sqrt(1 + x^2), x e^(x^2/2) = r, from
 * r = (K(ti) + K(to)) / sqrt(8 pi) >= 0.  For r <= BF_HE_R_SER = 0.01 the
 * series x = r (1 - t/2 + 5 t^2/8 - 49 t^3/48), t = r^2 (of y = e^(-t y^2 / 2),
 * y = x / r; the next term is below 2 t^4 < 2e-16), within 3.2e-16 of the
 * root (against a long double Newton; tests/test_he.c, newton_x).  Above,
 * Newton on ln x + x^2/2 - ln r (no overflow for any r), from r when r <= 1
 * (the right of the root; the first step lands left of it and the rest
 * increase monotonically) and from max(sqrt(2 ln r), 0.75) otherwise
 * (monotone on either side of x = 1).  A lane stops after a step
 * |dx| <= 1e-8 x: with F = ln x + x^2/2 - ln r the relative error after a
 * step is (x F'' / 2F') (dx / x)^2 and |x F'' / 2F'| = |x^2 - 1| / (2 (1 + x^2))
 * < 1/2, so x is then within 5e-17 of the root (and rounding: 1.3e-15
 * measured).  A vector whose every r is at most 0.01 takes no logarithm. */
#define BF_HE_R_SER 0.01

BF_FN BF_REAL bf_he_newton_x(BF_REAL r)
{
    BF_REAL rs = fmax(r, BF_TINY), t = rs * rs;
    BF_REAL xs = rs * (1.0 + t * (-0.5 + t * (0.625 + t * (-49.0 / 48.0))));
    if (!BF_ANY(rs > BF_HE_R_SER))
        return xs;
    BF_REAL lr = log(rs);
    BF_REAL x = BF_SEL(rs, fmax(sqrt(2.0 * fmax(lr, 0.0)), BF_R(0.75)), rs > 1.0);
    BF_REAL act = BF_SEL(BF_R(0.0), BF_R(1.0), rs > BF_HE_R_SER);
    for (int it = 0; it < 60 && BF_ANY(act > 0.0); it++) {
        BF_REAL dx = (log(x) + 0.5 * x * x - lr) * x / (1.0 + x * x);
        x = BF_SEL(x, fmax(x - dx, 0.5 * x), act > 0.0);
        act = BF_SEL(act, BF_R(0.0), fabs(dx) <= 1e-8 * x);
    }
    return BF_SEL(xs, x, rs > BF_HE_R_SER);
}

/* d(m) = ln(T_{m+1} / T_m), T_m = g^m e^-g / (m! m) e^(-a/m): decreasing in m. */
BF_FN BF_REAL bf_he_dlog(BF_REAL m, BF_REAL lng, BF_REAL a)
{
    return lng - log((m + 1.0) * (m + 1.0) / m) + a / (m * (m + 1.0));
}

/* sum_{m>=1} exp(ln T_m + lk) for the lanes where act > 0 (the others: 0),
 * for g = min(g, 19) > 0 with lng = ln g, a >= 0 with la ~ ln a (only a
 * starting point depends on la).  See the header comment; a lane whose peak
 * term puts less than e^ldead into the value (lpk + lk < ldead) is dead: 0,
 * not summed.  ldead is BF_HE_LN_DEAD (where the value underflows) but in a
 * pass's bin rows (bf_he_row_floor).
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
    const double mmax = (double)BF_HE_MMAX, lnmmax = BF_HE_LN_MMAX;
    if (deriv) {
        *vg = BF_R(0.0);
        *va = BF_R(0.0);
        *lpko = BF_R(0.0);
        *sumo = BF_R(0.0);
    }
    if (!BF_ANY(act > 0.0))
        return BF_R(0.0);

    /* The continuous peak of ln T_m ~ m ln(g/m) + m - a/m: ln(m/g) = a/m^2,
     * Newton in y = ln m (concave increasing: monotone after the first step). */
    BF_REAL y = fmax(lng, 0.5 * (la - log(fmax(0.5 * la - lng, BF_R(1.0)))));
    y = fmin(fmax(y, 0.0), lnmmax);
    for (int it = 0; it < 3; it++) {
        BF_REAL e = a * exp(-2.0 * y);
        y = fmin(fmax(y - (y - lng - e) / (1.0 + 2.0 * e), 0.0), lnmmax);
    }
    BF_REAL m = fmin(fmax(floor(exp(y) + 0.5), BF_R(1.0)), BF_R(mmax));

    /* The exact discrete peak m*: d(m* - 1) > 0 >= d(m*) (or m* = 1, = mmax). */
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
    /* conv: m is the peak (a lane that hit a search cap is summed in full) */
    BF_REAL conv = BF_SEL(BF_R(1.0), BF_R(0.0), (up > 0.0) || (dn > 0.0));

    /* ln T at the peak (ln m! to ~1e-3 is enough here): too small -> 0. */
    BF_REAL x1 = m + 1.0;
    BF_REAL lpk = m * lng - ((x1 - 0.5) * log(x1) - x1 + BF_HE_LN_SQRT_2PI + 1.0 / (12.0 * x1))
                - g - a / m - log(m);
    act = BF_SEL(act, BF_R(0.0), (conv > 0.0) && (lpk + lk < ldead));
    if (deriv)
        *lpko = lpk;
    if (!BF_ANY(act > 0.0))
        return BF_R(0.0);

    /* First term within e^-40 of the peak: the curvature of ln T is at least
     * kap on [3, m*], so ln T(m* - w) <= ln T(m*) - kap w (w - 1) / 2. */
    BF_REAL kap = 2.0 * a / (x1 * x1 * x1) + (m - 1.0) / (m * x1);
    BF_REAL w = 0.5 + sqrt(0.25 + 80.0 / fmax(kap, BF_R(1e-300)));
    BF_REAL mlo = floor(m - w);
    mlo = BF_SEL(mlo, BF_R(1.0), (mlo < 3.0) || (conv <= 0.0));
    mlo = BF_SEL(BF_R(1e9), mlo, act > 0.0);
    int m0 = 1;
    while (m0 + 16 <= BF_HE_MMAX && !BF_ANY(mlo <= (double)(m0 + 16)))
        m0 += 16;
    while (m0 < BF_HE_MMAX && !BF_ANY(mlo <= (double)m0))
        m0++;

    /* The sum, while some lane is before its peak or above 1e-12 of its sum,
     * of the terms relative to the peak (exp's arguments stay in about
     * [-60, 0], away from its slow underflow paths; the clamps only guard
     * the finiteness of lanes that are not summed). */
    BF_REAL sum = BF_R(0.0), s1 = BF_R(0.0), sinv = BF_R(0.0);
    BF_REAL base = -g - lpk;
    for (int k = m0; k <= BF_HE_MMAX; k++) {
        double dk = (double)k, ik = 1.0 / dk;
        BF_REAL e = dk * lng - a * ik + (base - bf_he_lkk[k]);
        BF_REAL t = exp(fmin(fmax(e, BF_R(-700.0)), BF_R(700.0)));
        sum = BF_SEL(sum, sum + t, act > 0.0);
        if (deriv) {
            s1 = BF_SEL(s1, s1 + t * dk, act > 0.0);
            sinv = BF_SEL(sinv, sinv + t * ik, act > 0.0);
        }
        act = BF_SEL(act, BF_R(0.0), (m <= dk) && (t <= 1e-12 * sum));
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

/* The blend weight t of the rough limit (0 below g = 18, 1 above 19) and the
 * limit e^(lk - a/g) / g itself (g clamped to >= 18). */
BF_FN BF_REAL bf_he_blend_t(BF_REAL g)
{
    return fmin(fmax(g - BF_HE_G_LO, 0.0), 1.0);
}

BF_FN BF_REAL bf_he_limit(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL lk)
{
    return exp(lk - a / fmax(g, BF_HE_G_LO) - fmax(lng, BF_R(BF_HE_LN_G_LO)));
}

BF_FN BF_REAL bf_he_blend(BF_REAL t, BF_REAL ser, BF_REAL lim)
{
    return BF_SEL(BF_SEL((1.0 - t) * ser + t * lim, ser, t <= 0.0), lim, t >= 1.0);
}

/* The memo of a data pass (bf_he_series_memo, through bf_he_fd).  A data pass
 * walks the samples in table order, so consecutive vectors mostly share
 * theta_h and theta_d and differ in phi_d alone; g and a depend on phi_d
 * only through sigma, which is sigma0 exactly wherever r <= 1e-9 (a smooth
 * surface away from grazing).  There every lane of a vector has the (g, a) of
 * the previous vector's last lane to rounding.  With memo != NULL (a pass
 * keeps one per work-item, zeroed at its start, and gives it vector after
 * vector), the lanes of a channel whose g and a are within BF_HE_MEMO_TOL
 * (relative) of the memo's do not sum the series (only the other lanes do,
 * if any): they take the memo's lpk, sum and partials and carry them to
 * their own g, a to first order in ln V, as bf_he_fd carries its neighbours
 * (the remainder is below (m* 1e-12)^2 ~ 1e-19 relative; the carry itself is
 * ~1e-13).  Values then agree with bf_he to ~1e-13 relative, and depend on
 * where a work-item's run of samples starts only at that level.  A channel
 * whose last lane sums its series leaves that lane in the memo; a memo whose
 * lane was dead (too small to sum) serves only lanes dead as well.  (A vector
 * that straddles two bins thus sums one bin's window, not the union of
 * both.) */
#define BF_HE_FD_MARGIN 1.001
#define BF_HE_MEMO_TOL 1e-12

/* The logs of the constants of a pass's point that bf_he_fd_base and
 * bf_he_fd_channel use (scalar logs cost as much as the vector work of a
 * sample vector): made for (tau, lam[0..2]) = key, once per run of a pass
 * through the memo (key[0] = 0: not made yet; tau >= 1). */
typedef struct bf_he_pconst {
    double key[4];
    double lkl2[3], lkt2[3], l4kt2[3]; /* ln (2 pi / lam)^2, ln kt^2, ln 4 kt^2, kt = pi tau / (2 lam) */
    double ltau16;                     /* ln (tau^2 / 16)                     */
    double ldead[3];                   /* bf_he_series_x's ldead per channel: BF_HE_LN_DEAD,
                                        * raised in the bin rows (bf_he_row_floor) */
} bf_he_pconst;

BF_FN void bf_he_pconst_make(double tau, const double *lam, bf_he_pconst *pc)
{
    pc->key[0] = tau;
    for (int ch = 0; ch < 3; ch++) {
        double kl = 2.0 * BF_PI / lam[ch];
        double kt = BF_PI * tau / (2.0 * lam[ch]);
        pc->key[1 + ch] = lam[ch];
        pc->lkl2[ch] = log(kl * kl);
        pc->lkt2[ch] = log(kt * kt);
        pc->l4kt2[ch] = log(4.0 * (kt * kt));
    }
    pc->ltau16 = log(tau * tau / 16.0);
    for (int ch = 0; ch < 3; ch++)
        pc->ldead[ch] = BF_HE_LN_DEAD;
}

BF_FN int bf_he_pconst_for(const bf_he_pconst *pc, double tau, const double *lam)
{
    return pc->key[0] == tau && pc->key[1] == lam[0] && pc->key[2] == lam[1] && pc->key[3] == lam[2];
}

/* The series table of a bin (bf_he_tab_make, bf_he_tab_eval): a data pass
 * walks a (theta_h, theta_d) bin's samples one after another, and within a
 * bin a = pi^2 (tau/lam)^2 |v_xy|^2 is fixed (|v_xy| = 2 cos theta_d
 * sin theta_h) while g varies with sigma alone, never above the bin's g at
 * sigma = sigma0 (g_ref).  So
 *     V(g) = sum_m T_m(g) = e^(L - g) sum_{m=k}^{k+n-1} b_m y^m,  y = g / g_ref,
 * b_m = e^(ln T_m(g_ref) + g_ref - L) is a polynomial in y whose
 * coefficients are made once per bin and channel (n exps, a vector of them
 * at a time), and each
 * lane then costs n multiply-adds instead of a search for its peak and an
 * exp per term.  The table keeps c_j = b_{k+j} / (k+j), and one Horner pass
 * gives Q = sum c_j y^j with Q' and Q''/2, from which (D = y d/dy)
 *     sum (t_m / m) = y^k Q,  sum t_m = y^k (k Q + y Q'),
 *     sum m t_m = y^k (k^2 Q + (2k+1) y Q' + y^2 Q''):
 * the value and both partials of ln V (bf_he_series_x's).  All coefficients
 * are positive and y <= 1, so Horner loses nothing to cancellation (~n ulp).
 * The window: the terms at g_ref from the first within e^-BF_HE_TAB_HEAD of
 * its largest (the ones below put less than e^-680 of g_ref's largest term
 * into any lane's sum: y >= 0 and e^(g_ref - g) <= e^19) to the last within
 * e^-BF_HE_TAB_TAIL past it (for g <= g_ref the tail falls off faster still).
 * So a lane's V agrees with bf_he_series_x's, which stops at 1e-12 of the sum,
 * to that truncation (~3e-13 measured).
 * A pass opens a bin's table (bf_he_tab_open: the window and L, a few dozen
 * scalar terms) and fills its coefficients (bf_he_tab_fill: the exps) only
 * when a lane it serves is not dead: a lane's ln V is at most
 * lpk + ln n with lpk = k ln y + L - g (y <= 1, every b_m <= 1), and a lane
 * with lpk + lk < BF_HE_LN_DEAD is 0 (bf_he_tab_serve), as bf_he_series_x
 * leaves a lane whose peak term is that small.  At a sharp lobe most bins
 * far from the specular direction are dead (alum-bronze at its fit: 38% of
 * the table terms of a pass). */
#define BF_HE_TAB_HEAD 700.0
#define BF_HE_TAB_TAIL 45.0
/* A lane is in a table's bin when its a is the table's within this (relative;
 * the lanes of one bin differ by the rounding of their directions, and the
 * first-order carry in a covers that) and its g at most g_ref within
 * BF_HE_TAB_GTOL (g_ref is the bin's g at sigma0, to rounding). */
#define BF_HE_TAB_ATOL 1e-12
#define BF_HE_TAB_GTOL 1e-9

typedef struct bf_he_tab {
    double a, gref;       /* what it was made for (n = 0: nothing yet)        */
    double lngref, igref; /* ln g_ref, 1 / g_ref                              */
    double L;             /* ln of the largest T_m(g_ref) e^g_ref             */
    double k, n;          /* the window: m = k .. k + n - 1                   */
    double filled;        /* 1: c holds the window's coefficients             */
    double c[BF_HE_MMAX + 8]; /* c[j] = b_{k+j} / (k + j); the 8 past MMAX take
                               * the last vector's overreach in the kernel    */
} bf_he_tab;

/* ln(T_m(g_ref) e^g_ref) of one term, lng = ln g_ref: what bf_he_tab_make
 * searches (concave in m, as its log ratios bf_he_dlog decrease). */
BF_FN double bf_he_tab_l(int m, double lng, double a)
{
    double dm = (double)m;
    return dm * lng - a / dm - bf_he_lkk[m];
}

/* bf_he_tab_l of the BF_NLANES terms from m0 (m0 = 1 mod BF_NLANES, so the
 * load of bf_he_lkk stays inside it: BF_HE_MMAX is a multiple of 4 and 8). */
BF_FN BF_REAL bf_he_tab_lv(int m0, double lng, double a)
{
    BF_REAL mv = (double)m0 + BF_IOTA;
    return mv * lng - a / mv - BF_LOADC(bf_he_lkk + m0);
}

/* The first m in [lo, hi) whose l_m < thr is `below` (hi if none), on a
 * side of the peak where l_m is monotone (a bisection). */
BF_FN int bf_he_tab_cross(int lo, int hi, double lng, double a, double thr, int below)
{
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if ((bf_he_tab_l(mid, lng, a) < thr) == below)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* The window of the terms l_m at a and g_ref (lng = ln g_ref): the largest
 * term l_m* = *lmax, the first term k within `head` of it and the last
 * term *mend before the first past the peak that is more than `tail`
 * below it (BF_HE_MMAX if none); a table's (see bf_he_tab) with
 * BF_HE_TAB_HEAD and BF_HE_TAB_TAIL (bf_he_tab_window).  l_m is concave in m, so each is a bisection
 * on a monotone side: about 27 scalar terms instead of every term up to the
 * tail's end (a scan of m = 1 .. ~200 at a sharp lobe's bins, which cost as
 * much as the table's exps). */
BF_FN int bf_he_window(double a, double lng, double head, double tail, double *lmax, int *mend)
{
    int lo = 1, hi = BF_HE_MMAX; /* the peak: the first m with l_(m+1) <= l_m */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (bf_he_tab_l(mid + 1, lng, a) > bf_he_tab_l(mid, lng, a))
            lo = mid + 1;
        else
            hi = mid;
    }
    const int peak = lo;
    const double top = bf_he_tab_l(peak, lng, a);
    /* the tail: the first m past the peak below top - TAIL; the head: the
     * first m before it within HEAD of top (the peak itself if none) */
    *mend = bf_he_tab_cross(peak + 1, BF_HE_MMAX + 1, lng, a, top - tail, 1) - 1;
    *lmax = top;
    return bf_he_tab_cross(1, peak, lng, a, top - head, 0);
}

BF_FN int bf_he_tab_window(double a, double lng, double *lmax, int *mend)
{
    return bf_he_window(a, lng, BF_HE_TAB_HEAD, BF_HE_TAB_TAIL, lmax, mend);
}

/* The table for a and g_ref opened: its window (bf_he_tab_window), its
 * coefficients not made yet (bf_he_tab_fill). */
BF_FN void bf_he_tab_open(bf_he_tab *t, double a, double gref)
{
    double lng = log(gref), lmax;
    int mend;
    const int k = bf_he_tab_window(a, lng, &lmax, &mend);
    t->a = a;
    t->gref = gref;
    t->lngref = lng;
    t->igref = 1.0 / gref;
    t->L = lmax;
    t->k = (double)k;
    t->n = (double)(mend - k + 1);
    t->filled = 0.0;
}

/* The coefficients of an open table: the terms of its window BF_NLANES at a
 * time (bf_he_tab_lv). */
BF_FN void bf_he_tab_fill(bf_he_tab *t)
{
    const double a = t->a, lng = t->lngref, lmax = t->L;
    const int k = (int)t->k, mend = k + (int)t->n - 1;
    /* ln(T_m(g_ref) e^g_ref) into c[m - 1] for the window's vectors */
    for (int m0 = k - (k - 1) % BF_NLANES; m0 <= mend; m0 += BF_NLANES)
        BF_STORE(bf_he_tab_lv(m0, lng, a), t->c + (m0 - 1));
    /* c[j] from c[k - 1 + j]: a vector is loaded before it is stored over,
     * and k >= 1, so no later load reads a stored value */
    for (int j0 = 0; j0 <= mend - k; j0 += BF_NLANES) {
        BF_REAL mv = (double)(k + j0) + BF_IOTA;
        BF_STORE(exp(BF_LOADP(t->c + (k - 1 + j0)) - lmax) / mv, t->c + j0);
    }
    t->filled = 1.0;
}

/* The table for a and g_ref, opened and filled. */
BF_FN void bf_he_tab_make(bf_he_tab *t, double a, double gref)
{
    bf_he_tab_open(t, a, gref);
    bf_he_tab_fill(t);
}

/* lpk of bf_he_tab_eval: ln V - ln sum at gs <= g_ref (lngs = ln gs). */
BF_FN BF_REAL bf_he_tab_lpk(const bf_he_tab *t, BF_REAL gs, BF_REAL lngs)
{
    return t->k * (lngs - t->lngref) + (t->L - gs);
}

/* V = e^lpk sum at gs <= g_ref (lngs = ln gs) from filled table t, and the
 * partials of ln V in g and a (see bf_he_tab; the caller carries ln V from
 * t's a to the lane's). */
BF_FN void bf_he_tab_eval(const bf_he_tab *t, BF_REAL gs, BF_REAL lngs, BF_REAL *lpk,
                          BF_REAL *sum, BF_REAL *vg, BF_REAL *va)
{
    BF_REAL y = gs * t->igref;
    BF_REAL q0 = BF_R(0.0), q1 = BF_R(0.0), q2 = BF_R(0.0); /* Q, Q', Q''/2 */
    for (int j = (int)t->n - 1; j >= 0; j--) {
        q2 = q2 * y + q1;
        q1 = q1 * y + q0;
        q0 = q0 * y + t->c[j];
    }
    const double k = t->k;
    BF_REAL yq1 = y * q1;
    BF_REAL s0 = k * q0 + yq1;
    BF_REAL s1 = (k * k) * q0 + (2.0 * k + 1.0) * yq1 + 2.0 * (y * y) * q2;
    BF_REAL is0 = 1.0 / s0;
    *lpk = bf_he_tab_lpk(t, gs, lngs);
    *sum = s0;
    *vg = (s1 * is0) / gs - 1.0;
    *va = -(q0 * is0);
}

/* The lanes of need whose series table t serves (see bf_he_tab): 1 or 0. */
BF_FN BF_REAL bf_he_tab_lanes(const bf_he_tab *t, BF_REAL gs, BF_REAL aa, BF_REAL need)
{
    if (!(t->n > 0.0))
        return BF_R(0.0);
    return BF_SEL(BF_R(0.0), BF_R(1.0),
                  (need > 0.0) && (fabs(aa - t->a) <= BF_HE_TAB_ATOL * t->a)
                      && (gs <= t->gref * (1.0 + BF_HE_TAB_GTOL)));
}

/* The series of the lanes of tl > 0 from table t into *lpk, *sum, *vg, *va
 * and *ser = e^(lpk + lk) sum (bf_he_series_x's outputs), the others left;
 * lanes with lpk + lk < ldead are dead, as in bf_he_series_x (sum,
 * partials and value 0), and t is filled when another lane needs it. */
BF_FN void bf_he_tab_serve(bf_he_tab *t, BF_REAL tl, BF_REAL gs, BF_REAL lngs, BF_REAL aa,
                           BF_REAL lk, double ldead, BF_REAL *lpk, BF_REAL *sum, BF_REAL *vg,
                           BF_REAL *va,
                           BF_REAL *ser)
{
    BF_REAL dlpk = bf_he_tab_lpk(t, gs, lngs);
    BF_REAL live = BF_SEL(BF_R(0.0), BF_R(1.0), (tl > 0.0) && (dlpk + lk >= ldead));
    BF_REAL dead = BF_SEL(BF_R(0.0), BF_R(1.0), (tl > 0.0) && !(live > 0.0));
    if (BF_ANY(dead > 0.0)) {
        *lpk = BF_SEL(*lpk, dlpk, dead > 0.0);
        *sum = BF_SEL(*sum, BF_R(0.0), dead > 0.0);
        *vg = BF_SEL(*vg, BF_R(0.0), dead > 0.0);
        *va = BF_SEL(*va, BF_R(0.0), dead > 0.0);
        *ser = BF_SEL(*ser, BF_R(0.0), dead > 0.0);
    }
    if (!BF_ANY(live > 0.0))
        return;
    if (!(t->filled > 0.0))
        bf_he_tab_fill(t);
    BF_REAL tlpk, tsum, tvg, tva;
    bf_he_tab_eval(t, gs, lngs, &tlpk, &tsum, &tvg, &tva);
    tlpk = tlpk + tva * (aa - t->a); /* to the lane's own a, to first order */
    *lpk = BF_SEL(*lpk, tlpk, live > 0.0);
    *sum = BF_SEL(*sum, tsum, live > 0.0);
    *vg = BF_SEL(*vg, tvg, live > 0.0);
    *va = BF_SEL(*va, tva, live > 0.0);
    *ser = BF_SEL(*ser, tsum * exp(fmin(tlpk + lk, BF_R(700.0))), live > 0.0);
}

/* The series at one (a, g): where every lane of a vector that needs a series
 * is flat (sigma = sigma0, so g is its bin's g_ref) with the (g, a) of its
 * last lane (to BF_HE_MEMO_TOL; at a smooth point every table a pass made
 * was for such lanes alone: alum-bronze at its fit), the pass sums that one series
 * as a scalar, BF_NLANES terms at a time, instead of making the bin's table
 * (whose head reaches e^-BF_HE_TAB_HEAD below the largest term for lanes
 * at g far below g_ref) and a Horner pass per lane.  Its terms: those
 * within e^-BF_HE_PT_EDGE of the largest on either side (what it leaves out
 * is below 400 e^-45 ~ 1e-17 of the sum).  It gives *lpk (ln of the
 * largest term T_m*), *sum (of T_m / T_m*) and the partials of ln V as
 * bf_he_series_x gives them for a lane at (g, a); a series whose
 * lpk + lkmax < ldead is dead (sum and partials 0, no exps), as
 * bf_he_series_x leaves such a lane. */
#define BF_HE_PT_EDGE 45.0

BF_FN void bf_he_series_point(double a, double g, double lkmax, double ldead, double *lpk,
                              double *sum, double *vg, double *va)
{
    double lng = log(g), top;
    int mend;
    const int k = bf_he_window(a, lng, BF_HE_PT_EDGE, BF_HE_PT_EDGE, &top, &mend);
    *lpk = top - g;
    *sum = *vg = *va = 0.0;
    if (*lpk + lkmax < ldead)
        return;
    BF_REAL s0 = BF_R(0.0), s1 = BF_R(0.0), si = BF_R(0.0);
    for (int m0 = k - (k - 1) % BF_NLANES; m0 <= mend; m0 += BF_NLANES) {
        BF_REAL mv = (double)m0 + BF_IOTA;
        BF_REAL l = bf_he_tab_lv(m0, lng, a);
        BF_REAL t = BF_SEL(BF_R(0.0), exp(fmin(l - top, BF_R(0.0))), (mv >= (double)k) && (mv <= (double)mend));
        s0 += t;
        s1 += t * mv;
        si += t / mv;
    }
    const double S0 = BF_HSUM(s0);
    *sum = S0;
    *vg = BF_HSUM(s1) / (g * S0) - 1.0;
    *va = -(BF_HSUM(si) / S0);
}

/* The lanes of `one` (every one at (gl, al) to BF_HE_MEMO_TOL) from the
 * series at (gl, al) (bf_he_series_point), carried to their own g and a to
 * first order in ln V as the memo carries its lanes, into *lpk, *sum, *vg,
 * *va and *ser (bf_he_series_x's outputs); the other lanes left. */
BF_FN void bf_he_point_serve(BF_REAL one, double gl, double al, BF_REAL gs, BF_REAL aa,
                             BF_REAL lk, double ldead, BF_REAL *lpk, BF_REAL *sum, BF_REAL *vg,
                             BF_REAL *va,
                             BF_REAL *ser)
{
    double plpk, psum, pvg, pva;
    bf_he_series_point(al, gl, bf_max_where(lk, one, -INFINITY), ldead, &plpk, &psum, &pvg,
                       &pva);
    BF_REAL l = plpk + (pvg * (gs - gl) + pva * (aa - al));
    *lpk = BF_SEL(*lpk, l, one > 0.0);
    *sum = BF_SEL(*sum, BF_R(psum), one > 0.0);
    *vg = BF_SEL(*vg, BF_R(pvg), one > 0.0);
    *va = BF_SEL(*va, BF_R(pva), one > 0.0);
    *ser = BF_SEL(*ser, psum * exp(fmin(l + lk, BF_R(700.0))), one > 0.0);
}

/* He's lobe parameters: the forward-difference neighbours of a pass, at most. */
#define BF_HE_NP 3

typedef struct bf_he_memo {
    bf_he_pconst pc;            /* the point's constants (see above)        */
    double g[3], a[3];          /* the (clamped) g and a of the stored lane */
    double ok[3];               /* 1: a lane is stored (active, peak found) */
    double lpk[3], sum[3];      /* its series e^lpk sum (sum 0: dead)       */
    double vg[3], va[3];        /* the partials of ln V there               */
    double hits;                /* channel-vectors served wholly by the memo */
    /* the bin rows (bf_he_bin_rows; rows NULL: none): a flat lane's
     * K cos ti cos to per bin, field f of bin hd at rows[f * nrows + hd] */
    BF_GLOBAL const double *rows;
    int nrows;
    /* the bin table the rows were made from, and the least BF_B_COTLO of a
     * bin whose samples are all flat at p0 for certain (bf_he_flat_sure) */
    BF_GLOBAL const double *bins;
    double cot_sure;
    BF_REAL vhd;                /* the bins hd of the vector's lanes         */
    double bk[1 + BF_HE_NP][3]; /* the row of the last bin served whole      */
    double bhits;               /* vectors served by the rows                */
    double bsure;               /* of them, found flat by the bin table      */
    double bgen;                /* 1 + the bin of bk (0: none)               */
    /* the series tables (bf_he_tab), one per channel */
    bf_he_tab tab[3];
    double thits;               /* channel-vectors whose lanes that needed a
                                 * series all took it from a table          */
} bf_he_memo;

BF_FN void bf_he_memo_clear(bf_he_memo *m)
{
    for (int c = 0; c < 3; c++) {
        m->pc.key[1 + c] = m->pc.lkl2[c] = m->pc.lkt2[c] = m->pc.l4kt2[c] = 0.0;
    }
    m->pc.key[0] = m->pc.ltau16 = 0.0;
    for (int c = 0; c < 3; c++) {
        m->g[c] = m->a[c] = m->ok[c] = 0.0;
        m->lpk[c] = m->sum[c] = m->vg[c] = m->va[c] = 0.0;
    }
    m->hits = 0.0;
    m->rows = 0;
    m->nrows = 0;
    m->bins = 0;
    m->cot_sure = 0.0;
    m->vhd = BF_R(0.0);
    for (int j = 0; j <= BF_HE_NP; j++)
        for (int c = 0; c < 3; c++)
            m->bk[j][c] = 0.0;
    m->bhits = 0.0;
    m->bsure = 0.0;
    m->bgen = 0.0;
    for (int c = 0; c < 3; c++) /* the coefficients are read only up to n */
        m->tab[c].a = m->tab[c].gref = m->tab[c].lngref = m->tab[c].igref = m->tab[c].L =
            m->tab[c].k = m->tab[c].n = m->tab[c].filled = 0.0;
    m->thits = 0.0;
}

/* The lanes of need that a pass's series tables serve, for
 * bf_he_series_memo (1 in those lanes, returned; their series into *lpk,
 * *sum, *vg, *va and *ser, bf_he_series_x's outputs): those that the
 * channel's table t covers (a vector that straddles two bins: those of the
 * bin before), then, when the last lane needs a series, the rest flat at
 * its (g, a) from that one series (bf_he_series_point), else those of its
 * bin from a table made for it. */
BF_FN BF_REAL bf_he_memo_tables(bf_he_tab *t, BF_REAL need, BF_REAL gs, BF_REAL lngs, BF_REAL aa,
                                BF_REAL lk, double ldead, BF_REAL gtop, BF_REAL *lpk,
                                BF_REAL *sum, BF_REAL *vg, BF_REAL *va, BF_REAL *ser)
{
    BF_REAL tl = bf_he_tab_lanes(t, gs, aa, need);
    if (BF_ANY(tl > 0.0))
        bf_he_tab_serve(t, tl, gs, lngs, aa, lk, ldead, lpk, sum, vg, va, ser);
    if (!(BF_LAST(need) > 0.0) || BF_LAST(tl) > 0.0)
        return tl;
    double gl = BF_LAST(gs), al = BF_LAST(aa);
    BF_REAL want = BF_SEL(need, BF_R(0.0), tl > 0.0);
    BF_REAL one = BF_SEL(BF_R(0.0), BF_R(1.0),
                         (want > 0.0) && (fabs(gs - gl) <= BF_HE_MEMO_TOL * gl)
                             && (fabs(aa - al) <= BF_HE_MEMO_TOL * al)
                             && (gs >= fmin(gtop, BF_R(BF_HE_G_HI)) * (1.0 - BF_HE_MEMO_TOL)));
    if (!BF_ANY((want > 0.0) && !(one > 0.0))) {
        bf_he_point_serve(one, gl, al, gs, aa, lk, ldead, lpk, sum, vg, va, ser);
        return BF_SEL(tl, BF_R(1.0), one > 0.0);
    }
    bf_he_tab_open(t, al, fmin(fmax(BF_LAST(gtop), gl), BF_HE_G_HI));
    BF_REAL tn = bf_he_tab_lanes(t, gs, aa, want);
    bf_he_tab_serve(t, tn, gs, lngs, aa, lk, ldead, lpk, sum, vg, va, ser);
    return BF_SEL(tl, BF_R(1.0), tn > 0.0);
}

/* The series of one channel ch for the lanes where act > 0, at gs = min(g, 19)
 * with lngs = ln gs (see bf_he_series_x for a, la, lk and deriv).  With a
 * memo (deriv must then be 1) the lanes it serves take its series carried to
 * their g and a; the others take it from the channel's series table when it
 * covers them (bf_he_tab: same a, g <= its g_ref), made anew for the last
 * lane when that lane needs a series the table does not cover (gtop: the
 * lane's g at sigma = sigma0, the largest its bin has), and sum it
 * (bf_he_series_x) only when neither serves them; the memo takes the last
 * lane if that one needed a series (see above).  With deriv, the partials of
 * ln V go to *vg_out and *va_out (0 where V is 0). */
BF_FN BF_REAL bf_he_series_memo(BF_REAL gs, BF_REAL lngs, BF_REAL aa, BF_REAL la, BF_REAL lk,
                                double ldead, BF_REAL gtop, BF_REAL act, int deriv,
                                bf_he_memo *memo, int ch, BF_REAL *vg_out, BF_REAL *va_out)
{
    /* hl: the lanes the memo serves; the others (that need it) sum */
    BF_REAL hl = BF_R(0.0), x = BF_R(0.0);
    if (memo && memo->ok[ch] > 0.0) {
        x = memo->vg[ch] * (gs - memo->g[ch]) + memo->va[ch] * (aa - memo->a[ch]);
        /* a memo that was not summed (dead) serves only lanes dead as well */
        hl = BF_SEL(BF_R(0.0), BF_R(1.0),
                    (fabs(gs - memo->g[ch]) <= BF_HE_MEMO_TOL * memo->g[ch])
                        && (fabs(aa - memo->a[ch]) <= BF_HE_MEMO_TOL * memo->a[ch])
                        && ((memo->sum[ch] > 0.0)
                            || (memo->lpk[ch] + lk < ldead)));
    }
    BF_REAL need = BF_SEL(act, BF_R(0.0), hl > 0.0);
    /* the served lanes' values, before the memo takes a new lane */
    BF_REAL hser = BF_R(0.0);
    double hvg = 0.0, hva = 0.0;
    if (BF_ANY(hl > 0.0)) {
        hser = memo->sum[ch] * exp(fmin(memo->lpk[ch] + lk + x, BF_R(700.0)));
        hser = BF_SEL(BF_R(0.0), hser, act > 0.0);
        hvg = memo->vg[ch];
        hva = memo->va[ch];
    }
    BF_REAL ser = BF_R(0.0), vg = BF_R(0.0), va = BF_R(0.0);
    if (BF_ANY(need > 0.0)) {
        BF_REAL lpk = BF_R(0.0), sum = BF_R(0.0), tl = BF_R(0.0);
        if (memo)
            tl = bf_he_memo_tables(&memo->tab[ch], need, gs, lngs, aa, lk, ldead, gtop, &lpk, &sum,
                                   &vg, &va, &ser);
        BF_REAL sx = BF_SEL(need, BF_R(0.0), tl > 0.0); /* the lanes that sum */
        if (BF_ANY(sx > 0.0)) {
            BF_REAL xlpk = BF_R(0.0), xsum = BF_R(0.0), xvg = BF_R(0.0), xva = BF_R(0.0);
            BF_REAL xser = bf_he_series_x(gs, lngs, aa, la, lk, ldead, sx, deriv, &xvg, &xva,
                                          &xlpk, &xsum);
            lpk = BF_SEL(lpk, xlpk, sx > 0.0);
            sum = BF_SEL(sum, xsum, sx > 0.0);
            vg = BF_SEL(vg, xvg, sx > 0.0);
            va = BF_SEL(va, xva, sx > 0.0);
            ser = BF_SEL(ser, xser, sx > 0.0);
        } else if (memo) {
            memo->thits += 1.0;
        }
        if (memo && BF_LAST(need) > 0.0) {
            memo->ok[ch] = 1.0;
            memo->g[ch] = BF_LAST(gs);
            memo->a[ch] = BF_LAST(aa);
            memo->lpk[ch] = BF_LAST(lpk);
            memo->sum[ch] = BF_LAST(sum);
            memo->vg[ch] = BF_LAST(vg);
            memo->va[ch] = BF_LAST(va);
        }
    } else if (memo && BF_ANY(act > 0.0)) {
        memo->hits += 1.0;
    }
    if (BF_ANY(hl > 0.0)) {
        ser = BF_SEL(ser, hser, hl > 0.0);
        vg = BF_SEL(vg, BF_R(hvg), hl > 0.0);
        va = BF_SEL(va, BF_R(hva), hl > 0.0);
    }
    *vg_out = vg;
    *va_out = va;
    return ser;
}

/* e^lk D / (pi tau / (2 lam))^2 of one channel from g > 0 with lng = ln g and
 * a >= 0 with la ~ ln a: the series below g = 18, the rough limit lim (the
 * caller's e^(lk - a/g) / g, used where g > 18) above 19, linear in g in
 * between: the one place the two are blended (bf_he_D and bf_he_fd both
 * come here).  The series is summed, at min(g, 19), where g < 19 margin:
 * margin 1 for a value alone, BF_HE_FD_MARGIN when bf_he_fd will carry
 * neighbours from it.  *V gets the series; memo, ch, deriv, *vg, *va: see
 * bf_he_series_memo.  Finite wherever e^lk D is (lanes on one side never see
 * the other side's value). */
BF_FN BF_REAL bf_he_dblend(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL la, BF_REAL lk,
                           double ldead, BF_REAL lim, BF_REAL gtop, double margin, int deriv,
                           bf_he_memo *memo, int ch, BF_REAL *V, BF_REAL *vg, BF_REAL *va)
{
    BF_REAL t = bf_he_blend_t(g);
    BF_REAL act = BF_SEL(BF_R(0.0), BF_R(1.0), g < BF_HE_G_HI * margin);
    *V = bf_he_series_memo(fmin(g, BF_HE_G_HI), fmin(lng, BF_R(BF_HE_LN_G_HI)), a, la, lk, ldead,
                           gtop, act, deriv, memo, ch, vg, va);
    return bf_he_blend(t, *V, lim);
}

/* bf_he_dblend of one lane set with its own rough limit, no memo, no partials. */
BF_FN BF_REAL bf_he_dscaled(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL la, BF_REAL lk)
{
    BF_REAL lim = BF_R(0.0);
    if (BF_ANY(bf_he_blend_t(g) > 0.0))
        lim = bf_he_limit(g, lng, a, lk);
    BF_REAL V, vg, va;
    return bf_he_dblend(g, lng, a, la, lk, BF_HE_LN_DEAD, lim, g, 1.0, 0, (bf_he_memo *)0, 0, &V,
                        &vg, &va);
}

/* The distribution D(g, a) of one wavelength lam (um) for tau (um), g > 0, a >= 0. */
BF_FN BF_REAL bf_he_D(BF_REAL g, BF_REAL a, double tau, double lam)
{
    double k = BF_PI * tau / (2.0 * lam);
    BF_REAL gs = fmax(g, BF_TINY), as = fmax(a, 0.0);
    return bf_he_dscaled(gs, log(gs), as, log(fmax(as, BF_TINY)), BF_R(log(k * k)));
}

/* ---- K in stages: the direction pair, then (tau, sigma0), then n, then the
 * per-channel arguments of D.  bf_he runs them in order; bf_he_fd (a value
 * and its forward-difference neighbours) reuses what a parameter step leaves
 * unchanged. */

/* What depends on the directions only. */
typedef struct bf_he_dir {
    BF_REAL ci, si, co, so; /* cosines (floored) and sines of ti, to   */
    BF_REAL c;              /* cos theta_b = |v| / 2                    */
    BF_REAL vz, vxy2;       /* v_z, |v_xy|^2                            */
    BF_REAL lg2;            /* 2 ln(v.v / v_z) = ln G                   */
    BF_REAL lvxy2;          /* ln |v_xy|^2 (floored)                    */
} bf_he_dir;

BF_FN void bf_he_dir_make(const bf_geom *g, bf_he_dir *d)
{
    BF_REAL ci = fmax(g->iz, BF_HE_COS_MIN), co = fmax(g->oz, BF_HE_COS_MIN);
    BF_REAL si = sqrt(g->ix * g->ix + g->iy * g->iy);
    BF_REAL so = sqrt(g->ox * g->ox + g->oy * g->oy);
    BF_REAL vx = g->ix + g->ox, vy = g->iy + g->oy, vz = ci + co;
    BF_REAL vxy2 = vx * vx + vy * vy;
    BF_REAL vv = vxy2 + vz * vz;
    d->ci = ci;
    d->si = si;
    d->co = co;
    d->so = so;
    d->c = fmin(fmax(0.5 * sqrt(vv), BF_HE_COS_MIN), 1.0);
    d->vz = vz;
    d->vxy2 = vxy2;
    d->lg2 = 2.0 * log(vv / vz);
    d->lvxy2 = log(fmax(vxy2, BF_R(1e-300)));
}

/* The geometrical factor G = (v.v / v_z)^2, v = wi + wo (see the header
 * comment), as K uses it: e^(ln G) of bf_he_dir_make. */
BF_FN BF_REAL bf_he_geometry(const bf_geom *g)
{
    bf_he_dir d;
    bf_he_dir_make(g, &d);
    return exp(d.lg2);
}

/* What depends on (tau, sigma0) too: S(ti), S(to), S(ti) / cos ti, S(to) / cos to
 * (within [1e-3, 1e3]-ish) and the effective roughness sigma; with deriv, also what
 * bf_he_rough_step needs to carry them to a nearby (tau, sigma0).  With flat,
 * every lane takes the flat values (S = 1, sigma = sigma0) whatever its u:
 * what a bin's row of a pass is made with (bf_he_bin_rows). */
typedef struct bf_he_rough {
    int flat;                       /* 1: u >= BF_HE_U_FLAT in every lane and
                                     * both directions (see bf_he_rough_make) */
    BF_REAL Si, So;                 /* S(ti), S(to)                        */
    BF_REAL shi, sho, sigma;
    BF_REAL ui, uo, ei, eo, xi, xo; /* u, erfc(u), exp(-u^2) of ti and to  */
    BF_REAL dshi, dsho;             /* d(S(t) / cos t) / du                */
    BF_REAL r, x;                   /* sigma's r and x                     */
    BF_REAL tani, tano;             /* tan ti, tan to (r's weights)        */
    BF_REAL xk, xr;                 /* xk = x / (1 + x^2): dx per d ln r at the
                                     * root, and -d ln sigma per dx; xr = xk / r:
                                     * dx per dr                           */
} bf_he_rough;

BF_FN void bf_he_rough_make(const bf_he_dir *d, double tau, double sigma0, int deriv,
                            int flat, bf_he_rough *r)
{
    BF_REAL ui = bf_he_u(d->ci, d->si, tau, sigma0), uo = bf_he_u(d->co, d->so, tau, sigma0);
    r->flat = flat || !BF_ANY((ui < BF_HE_U_FLAT) || (uo < BF_HE_U_FLAT));
    if (r->flat) {
        /* erfc and e^(-u^2) are 0 (bf_he_erfc2): S = 1, r = 0, x = BF_TINY
         * (bf_he_newton_x), sigma = sigma0, the partials in u 0: the values
         * of the general path below, without its divisions */
        r->Si = r->So = BF_R(1.0);
        r->shi = 1.0 / d->ci;
        r->sho = 1.0 / d->co;
        r->sigma = BF_R(sigma0);
        if (deriv) {
            r->ui = ui;
            r->uo = uo;
            r->ei = r->eo = r->xi = r->xo = BF_R(0.0);
            r->dshi = r->dsho = BF_R(0.0);
            r->r = BF_R(0.0);
            r->x = BF_R(BF_TINY);
            r->tani = r->tano = r->xk = r->xr = BF_R(0.0);
        }
        return;
    }
    BF_REAL ei, eo, xi, xo;
    bf_he_erfc2(ui, &ei, &xi);
    bf_he_erfc2(uo, &eo, &xo);
    r->Si = bf_he_shadow1x(ui, ei, xi);
    r->So = bf_he_shadow1x(uo, eo, xo);
    r->shi = r->Si / d->ci;
    r->sho = r->So / d->co;
    BF_REAL tani = d->si / d->ci, tano = d->so / d->co;
    BF_REAL rr = (tani * ei + tano * eo) * (1.0 / sqrt(8.0 * BF_PI));
    BF_REAL x = bf_he_newton_x(rr);
    r->sigma = sigma0 / sqrt(1.0 + x * x);
    if (deriv) {
        r->tani = tani;
        r->tano = tano;
        r->xk = x / (1.0 + x * x);
        r->xr = r->xk / fmax(rr, BF_R(BF_TINY));
        r->ui = ui;
        r->uo = uo;
        r->ei = ei;
        r->eo = eo;
        r->xi = xi;
        r->xo = xo;
        r->dshi = bf_he_dshadow1(ui, ei, xi) / d->ci;
        r->dsho = bf_he_dshadow1(uo, eo, xo) / d->co;
        r->r = rr;
        r->x = x;
    }
}

/* The shadowing S = S(theta_i) S(theta_o) of a direction pair, as K uses it. */
BF_FN BF_REAL bf_he_shadowing(const bf_geom *g, double tau, double sigma0)
{
    bf_he_dir d;
    bf_he_rough r;
    bf_he_dir_make(g, &d);
    bf_he_rough_make(&d, tau, sigma0, 0, 0, &r);
    return r.Si * r.So;
}

/* The effective roughness sigma of a direction pair, as K uses it. */
BF_FN BF_REAL bf_he_sigma(const bf_geom *g, double tau, double sigma0)
{
    bf_he_dir d;
    bf_he_rough r;
    bf_he_dir_make(g, &d);
    bf_he_rough_make(&d, tau, sigma0, 0, 0, &r);
    return r.sigma;
}

/* r0 (made with deriv at (tau0, sigma00)) carried to (tau, sigma0) nearby,
 * to first order in the steps: u scales with tau / sigma0 (so du = u0 times
 * the ratio's step, exactly but for rounding), S(t) / cos t by dS/du, erfc by
 * -2 e^(-u^2) / sqrt(pi), r by its weights tan t, x by one Newton step on
 * ln x + x^2/2 = ln r from r0's root (dx = x dr / (r (1 + x^2))), sigma by
 * d ln sigma = d ln sigma0 - x dx / (1 + x^2).  No exp, erfc, log, square
 * root or division per lane.  (It sets shi, sho and sigma: all that a
 * neighbour uses.) */
BF_FN void bf_he_rough_step(const bf_he_rough *r0, double tau0, double sigma00, double tau,
                            double sigma0, bf_he_rough *r)
{
    r->flat = r0->flat;
    if (r0->flat) { /* every partial is 0 and x = BF_TINY: the general path's values */
        r->shi = r0->shi;
        r->sho = r0->sho;
        r->sigma = BF_R(sigma0);
        return;
    }
    /* u'/u - 1; u = 1e10 is the normal's clamp (bf_he_u), where u stays */
    const double du = (tau * sigma00 - tau0 * sigma0) / (tau0 * sigma0);
    BF_REAL dui = BF_SEL(r0->ui * du, BF_R(0.0), r0->ui >= 1e10);
    BF_REAL duo = BF_SEL(r0->uo * du, BF_R(0.0), r0->uo >= 1e10);
    r->shi = r0->shi + r0->dshi * dui;
    r->sho = r0->sho + r0->dsho * duo;
    BF_REAL dr = (r0->tani * r0->xi * dui + r0->tano * r0->xo * duo)
               * (-2.0 / (BF_SQRT_PI * sqrt(8.0 * BF_PI)));
    BF_REAL dx = r0->xr * dr;
    r->sigma = (r0->sigma * (sigma0 / sigma00)) * (1.0 - r0->xk * dx);
}

/* What bf_he_fd computes at p[0] and its neighbours are carried from. */
typedef struct bf_he_base {
    bf_he_dir d;
    bf_he_rough r;                /* made with deriv                          */
    BF_REAL F;                    /* Fresnel at n                             */
    BF_REAL fs, ifs;              /* F S(ti) S(to) / (pi cos ti cos to), 1 / fs */
    BF_REAL lc;                   /* ln fs + ln G                             */
    BF_REAL zero;                 /* 1 where fs underflows: K = 0             */
    BF_REAL sv, lsv2;             /* sigma v_z and 2 ln(sigma v_z)            */
    BF_REAL s0v;                  /* sigma0 v_z                               */
    double klmax2;                /* the largest (2 pi / lam)^2 of the channels */
    BF_REAL q0, lim0;             /* a / g and e^lk / g of the rough limit (see bf_he_fd_base) */
    /* per channel: the value before the zero flag, the series V (summed at
     * min(g, 19)) and its partials, the limit L, min(g, 19), a, max(g, 18),
     * a / max(g, 18) */
    BF_REAL Kr[3], V[3], Vg[3], Va[3], L[3], g0[3], a0[3], gl[3], agl[3];
} bf_he_base;

/* The direction pair, the shadowing and sigma (with their partials), F and
 * the rough limit shared by the channels, at p0 = (tau, sigma0, n) (flat: see
 * bf_he_rough_make). */
BF_FN void bf_he_fd_base(const bf_geom *g, const double *p0, const double *lam,
                         const bf_he_pconst *pc, int flat, bf_he_base *b)
{
    const double tau = p0[0], sigma0 = p0[1], n = p0[2];
    bf_he_dir_make(g, &b->d);
    bf_he_rough_make(&b->d, tau, sigma0, 1, flat, &b->r);
    b->F = bf_he_fresnel(b->d.c, n);
    b->fs = b->F * b->r.shi * b->r.sho * (1.0 / BF_PI);
    b->ifs = 1.0 / fmax(b->fs, BF_TINY);
    b->lc = log(fmax(b->fs, BF_TINY)) + b->d.lg2;
    b->zero = BF_SEL(BF_R(0.0), BF_R(1.0), b->fs < BF_TINY);
    b->sv = b->r.sigma * b->d.vz;             /* > 1e-106: g never underflows */
    b->lsv2 = 2.0 * log(b->sv);
    b->s0v = sigma0 * b->d.vz;

    /* The rough limit e^(lk - a/g) / g is the same in every channel where
     * g >= 18: a/g = q0 = tau^2 |v_xy|^2 / (4 sv^2) and e^lk / g =
     * e^lc (tau / 4)^2 / sv^2 do not depend on lam (one exp for the three). */
    b->klmax2 = 0.0;
    for (int ch = 0; ch < 3; ch++)
        b->klmax2 = fmax(b->klmax2, (2.0 * BF_PI / lam[ch]) * (2.0 * BF_PI / lam[ch]));
    b->q0 = BF_R(0.0);
    b->lim0 = BF_R(0.0);
    if (BF_ANY(b->klmax2 * (b->sv * b->sv) > BF_HE_G_LO / BF_HE_FD_MARGIN)) {
        b->q0 = (0.25 * tau * tau) * b->d.vxy2 / (b->sv * b->sv);
        b->lim0 = exp(fmin(b->lc - b->q0 - b->lsv2 + pc->ltau16, BF_R(700.0)));
    }
}

/* K(p0) of channel ch (wavelength lam um): bf_he's operations, with the
 * partials of the series and what the neighbours need kept in b. */
BF_FN BF_REAL bf_he_fd_channel(bf_he_base *b, double tau, double lam, int ch,
                               const bf_he_pconst *pc, bf_he_memo *memo)
{
    double kl = 2.0 * BF_PI / lam;
    double kt = BF_PI * tau / (2.0 * lam);
    double kl2 = kl * kl, kt2 = kt * kt;
    BF_REAL gg = kl2 * (b->sv * b->sv), lng = pc->lkl2[ch] + b->lsv2, lk = b->lc + pc->lkt2[ch];
    BF_REAL aa = (4.0 * kt2) * b->d.vxy2, la = pc->l4kt2[ch] + b->d.lvxy2;
    BF_REAL lim = BF_R(0.0);
    b->gl[ch] = fmax(gg, BF_HE_G_LO);
    b->agl[ch] = BF_R(0.0);
    if (BF_ANY(gg > BF_HE_G_LO / BF_HE_FD_MARGIN)) {
        /* g in (18 / m, 18): the limit at the clamp g = 18 (for the neighbours) */
        BF_REAL below = BF_SEL(BF_R(0.0), BF_R(1.0), gg < BF_HE_G_LO);
        lim = b->lim0;
        if (BF_ANY((below > 0.0) && (gg > BF_HE_G_LO / BF_HE_FD_MARGIN))) {
            lim = BF_SEL(lim, bf_he_limit(gg, lng, aa, lk), below > 0.0);
            b->agl[ch] = aa / b->gl[ch];
        }
        lim = BF_SEL(lim, BF_R(0.0), gg <= BF_HE_G_LO / BF_HE_FD_MARGIN);
    }
    BF_REAL gtop = kl2 * (b->s0v * b->s0v); /* g at sigma = sigma0: the bin's largest */
    b->Kr[ch] = bf_he_dblend(gg, lng, aa, la, lk, pc->ldead[ch], lim, gtop, BF_HE_FD_MARGIN, 1,
                             memo, ch, &b->V[ch], &b->Vg[ch], &b->Va[ch]);
    b->L[ch] = lim;
    b->g0[ch] = fmin(gg, BF_HE_G_HI);
    b->a0[ch] = aa;
    return BF_SEL(b->Kr[ch], BF_R(0.0), b->zero > 0.0);
}

/* K at pj = (tau', sigma0', n'), a small step from p0, carried from b: see bf_he_fd. */
BF_FN void bf_he_fd_neighbour(const bf_he_base *b, const double *p0, const double *pj,
                              const double *lam, BF_REAL *Kj)
{
    const double tau = p0[0], sigma0 = p0[1], n = p0[2];
    const double tj = pj[0], s0j = pj[1], nj = pj[2];
    BF_REAL Fj = b->F;
    if (nj != n)
        Fj = bf_he_fresnel(b->d.c, nj);
    if (tj == tau && s0j == sigma0) {
        /* n alone: S, sigma, g, a unchanged; K scales with F */
        BF_REAL fsj = Fj * b->r.shi * b->r.sho * (1.0 / BF_PI);
        BF_REAL zj = BF_SEL(b->zero, BF_R(1.0), fsj < BF_TINY);
        BF_REAL rat = fsj * b->ifs;
        for (int ch = 0; ch < 3; ch++)
            Kj[ch] = BF_SEL(rat * b->Kr[ch], BF_R(0.0), zj > 0.0);
        return;
    }
    bf_he_rough rj;
    bf_he_rough_step(&b->r, tau, sigma0, tj, s0j, &rj);
    BF_REAL fsj = Fj * rj.shi * rj.sho * (1.0 / BF_PI);
    BF_REAL zj = BF_SEL(b->zero, BF_R(1.0), fsj < BF_TINY);
    BF_REAL rat = fsj * b->ifs;
    BF_REAL svj = rj.sigma * b->d.vz;
    /* e^(a/g - a'/g') g / g' of the limit, shared by the channels where
     * g, g' >= 18 (see bf_he_fd_base) */
    BF_REAL ej = BF_R(0.0);
    if (BF_ANY(b->klmax2 * (svj * svj) > BF_HE_G_LO)) {
        BF_REAL isv2 = 1.0 / (svj * svj);
        BF_REAL qj = (0.25 * tj * tj) * b->d.vxy2 * isv2;
        ej = exp(fmin(b->q0 - qj, BF_R(700.0))) * ((b->sv * b->sv) * isv2);
    }
    for (int ch = 0; ch < 3; ch++) {
        double kl = 2.0 * BF_PI / lam[ch];
        double kt0 = BF_PI * tau / (2.0 * lam[ch]), kt = BF_PI * tj / (2.0 * lam[ch]);
        double kl2 = kl * kl, kt2 = kt * kt;
        BF_REAL gj = kl2 * (svj * svj), aj = (4.0 * kt2) * b->d.vxy2;
        BF_REAL rc = rat * (kt2 / (kt0 * kt0));     /* e^(lk' - lk) */
        BF_REAL x = b->Vg[ch] * (gj - b->g0[ch]) + b->Va[ch] * (aj - b->a0[ch]); /* ~ ln(V' / V) */
        BF_REAL ser = (rc * b->V[ch]) * (1.0 + x * (1.0 + x * (0.5 + x * (1.0 / 6.0))));
        BF_REAL t = bf_he_blend_t(gj);
        BF_REAL lim = BF_R(0.0);
        if (BF_ANY(t > 0.0)) {
            lim = (b->L[ch] * rc) * ej;
            BF_REAL up = BF_SEL(BF_R(0.0), BF_R(1.0), (t > 0.0) && (b->g0[ch] < BF_HE_G_LO));
            if (BF_ANY(up > 0.0)) { /* from below the clamp: the general form */
                BF_REAL iglj = 1.0 / fmax(gj, BF_HE_G_LO);
                lim = BF_SEL(lim, (b->L[ch] * rc) * (exp(b->agl[ch] - aj * iglj) * (b->gl[ch] * iglj)),
                             up > 0.0);
            }
        }
        Kj[ch] = BF_SEL(bf_he_blend(t, ser, lim), BF_R(0.0), zj > 0.0);
    }
}

/* The (theta_h, theta_d) bins of a sample set, for a lobe whose value factors
 * on a bin (He where the shadowing is flat: bf_he_bin_rows).  Bin hd = the
 * MERL bin index / 180 (0 .. BF_NHD - 1); field f of bin hd at
 * bins[f * BF_NHD_PAD + hd]: the geometry of the set's first sample in the
 * bin, BF_B_COT, the largest over the bin's samples of
 * min(cot ti, cot to) (bf_he_cot_of_cos; 0 for a bin with no sample), and
 * BF_B_COTLO, the smallest (0 for a bin with no sample).  A pass's bin rows hold
 * BF_BK_FIELDS fields per bin (bf_he_bin_rows). */
enum {
    BF_B_IX, BF_B_IY, BF_B_IZ, BF_B_OX, BF_B_OY, BF_B_OZ, BF_B_NH, BF_B_VH,
    BF_B_COT, BF_B_COTLO,
    BF_BFIELDS
};
#define BF_NHD (90 * 90)
#define BF_NHD_PAD (BF_NHD + 8) /* a vector from the last bin stays inside */
#define BF_BK_FIELDS (3 * (1 + BF_HE_NP))

/* The bin rows of a data pass (bf_he_memo.rows).  Where the shadowing is flat
 * (u >= BF_HE_U_FLAT for both directions: S = 1, sigma = sigma0), K depends
 * on the sample through its (theta_h, theta_d) bin alone (F at cos theta_d,
 * G, g and a, the rough limit) and through the factor 1 / (cos ti cos to) of
 * S(ti) S(to) / (cos ti cos to); so do the neighbours (bf_he_rough_step keeps
 * S and sigma0's place there).  A pass therefore makes, once per bin of its
 * samples and point p[0..np], the row K cos ti cos to at each point and
 * channel (bf_he_bin_rows: the bin's geometry from the sample set's bin table,
 * BF_NLANES bins at a time, so the series of distinct bins fill a vector's
 * lanes), and a vector whose lanes are all flat takes K = row / (cos ti cos to):
 * no logarithm, exponential or series.  The lanes of a bin differ from the
 * table's sample by the rounding of their directions, so a served K differs
 * from its own evaluation by that rounding's effect (tests/test_he.c,
 * pass_memo: at most ~1e-12 relative, at K ~ 1e-148 where a large a
 * amplifies it), or is 0 below the rows' floor (bf_he_row_floor). */
typedef struct bf_he_flat {
    BF_REAL ci, co;   /* cos ti, cos to, floored as bf_he_dir_make floors them */
    BF_REAL lanes;    /* 1 in a lane whose shadowing is flat at p[0]            */
} bf_he_flat;

/* f's cosines, floored as bf_he_dir_make floors them. */
BF_FN void bf_he_flat_cos(const bf_geom *g, bf_he_flat *f)
{
    f->ci = fmax(g->iz, BF_HE_COS_MIN);
    f->co = fmax(g->oz, BF_HE_COS_MIN);
}

BF_FN void bf_he_flat_make(const bf_geom *g, double tau, double sigma0, bf_he_flat *f)
{
    bf_he_flat_cos(g, f);
    BF_REAL ui = bf_he_u(f->ci, sqrt(g->ix * g->ix + g->iy * g->iy), tau, sigma0);
    BF_REAL uo = bf_he_u(f->co, sqrt(g->ox * g->ox + g->oy * g->oy), tau, sigma0);
    f->lanes = BF_SEL(BF_R(0.0), BF_R(1.0), (ui >= BF_HE_U_FLAT) && (uo >= BF_HE_U_FLAT));
}

/* bf_he_flat_make's flags for a vector whose lanes all lie in one bin hd
 * whose every sample is flat at p0 = (tau, sigma0) for certain (its
 * smallest min(cot ti, cot to), BF_B_COTLO, at least BF_HE_SURE_MARGIN above
 * the threshold 2 BF_HE_U_FLAT sigma0 / tau: the samples' own u, computed
 * from other roundings of the same cotangent, are then >= BF_HE_U_FLAT): the
 * cosines alone, with no square root or division.  0 when it cannot say (f
 * left); the lanes are then bf_he_flat_make's. */
#define BF_HE_SURE_MARGIN 1e-6

BF_FN double bf_he_cot_sure(double tau, double sigma0)
{
    return (2.0 * BF_HE_U_FLAT) * sigma0 / tau * (1.0 + BF_HE_SURE_MARGIN);
}

BF_FN int bf_he_flat_sure(const bf_geom *g, BF_GLOBAL const double *bins, BF_REAL vhd,
                          double cot_sure, bf_he_flat *f)
{
    const double hd = BF_LAST(vhd);
    if (!bins || BF_ANY(vhd != hd) || !(bins[BF_B_COTLO * BF_NHD_PAD + (int)hd] >= cot_sure))
        return 0;
    bf_he_flat_cos(g, f);
    f->lanes = BF_R(1.0);
    return 1;
}

/* The factor q = 1 / (cos ti cos to) of a vector the rows serve: its K at
 * p[j] in channel c is row[j][c] q. */
BF_FN BF_REAL bf_he_bin_q(const bf_he_flat *f)
{
    return 1.0 / (f->ci * f->co);
}

/* The cotangent of the angle whose cosine is c, with bf_he_u's floors: a
 * lane is flat at (tau, sigma0) where min(cot ti, cot to) is at least
 * 2 BF_HE_U_FLAT sigma0 / tau (to rounding), and min(cot ti, cot to) is this
 * of min(cos ti, cos to) (to rounding: sin t = sqrt(1 - cos^2 t) for unit
 * directions).  The sample set's bin table keeps it of the largest
 * min(cos ti, cos to) over a bin (BF_B_COT). */
BF_FN BF_REAL bf_he_cot_of_cos(BF_REAL c)
{
    BF_REAL cf = fmax(c, BF_HE_COS_MIN);
    return cf / fmax(sqrt(fmax(1.0 - c * c, 0.0)), 1e-300);
}

/* K0 and Kj of a vector the rows serve whole (every lane in the bin of bk),
 * from its factor q. */
BF_FN void bf_he_bin_serve(const bf_he_memo *m, BF_REAL q, int np, BF_REAL *K0,
                           BF_REAL (*Kj)[3])
{
    for (int c = 0; c < 3; c++)
        K0[c] = m->bk[0][c] * q;
    for (int j = 0; j < np; j++)
        for (int c = 0; c < 3; c++)
            Kj[j][c] = m->bk[1 + j][c] * q;
}

/* bk from bin hd's row, for np neighbours. */
BF_FN void bf_he_bin_load(bf_he_memo *m, int hd, int np)
{
    for (int j = 0; j <= np; j++)
        for (int c = 0; c < 3; c++)
            m->bk[j][c] = m->rows[(3 * j + c) * m->nrows + hd];
    m->bgen = 1.0 + (double)hd;
}

/* K0 and Kj of a flat vector whose lanes lie in several bins: each lane's
 * row, times its q. */
BF_FN void bf_he_bin_gather(const bf_he_memo *m, BF_REAL q, int np, BF_REAL *K0,
                            BF_REAL (*Kj)[3])
{
    double hv[BF_NLANES], t[BF_NLANES];
    BF_STORE(m->vhd, hv);
    for (int j = 0; j <= np; j++)
        for (int c = 0; c < 3; c++) {
            for (int l = 0; l < BF_NLANES; l++)
                t[l] = m->rows[(3 * j + c) * m->nrows + (int)hv[l]];
            BF_REAL v = BF_LOADP(t) * q;
            if (j == 0)
                K0[c] = v;
            else
                Kj[j - 1][c] = v;
        }
}

/* K at p[0] and at p[1..np] of the lanes of g, every step of bf_he_fd
 * (below) but the rows; with flat, every lane flat (bf_he_rough_make). */
BF_FN void bf_he_fd_lanes(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                          const bf_he_pconst *pc, int flat, BF_REAL *K0, BF_REAL (*Kj)[3],
                          bf_he_memo *memo)
{
    bf_he_base b;
    bf_he_fd_base(g, p[0], lam, pc, flat, &b);
    for (int ch = 0; ch < 3; ch++)
        K0[ch] = bf_he_fd_channel(&b, p[0][0], lam[ch], ch, pc, memo);
    for (int j = 0; j < np; j++)
        bf_he_fd_neighbour(&b, p[0], p[1 + j], lam, Kj[j]);
}

/* The floor of a pass's rows.  At a smooth point most bins lie far from the
 * specular direction, where K is below its value at normal incidence by
 * e^-100 to e^-700 without reaching e^BF_HE_LN_DEAD, and summing their
 * series was most of the rows' work (blue-acrylic at its fit: half the bins,
 * 60% of the terms).  So the rows take a lane as dead (0) where its series'
 * peak term puts less into K than e^-BF_HE_ROW_FLOOR of K at normal
 * incidence (wi = wo = N) at p0, per channel: pc->ldead = max(BF_HE_LN_DEAD,
 * ln K_normal - BF_HE_ROW_FLOOR) (BF_HE_LN_DEAD where K_normal is 0).  A
 * served K then differs from bf_he's by less than
 * BF_HE_MMAX e^-BF_HE_ROW_FLOOR K_normal ~ 3.5e-24 K_normal (at most
 * BF_HE_MMAX terms, none above the peak; tests/test_he.c, pass_memo).  In a
 * pass's sums, such a sample's term K w rho is then below 3.5e-24 e^20 ~
 * 1.7e-15 of the term of a sample near normal incidence (a MERL table's
 * rho spans less than e^20): below the rounding of sums of 1e5 to 1e6
 * such terms.  Measured over the 100 MERL tables: every fit the same to
 * the bit, at e^-100 first and at e^-60 since (subset passes at
 * blue-acrylic's and brass's fits 5-9% faster than at e^-100). */
#define BF_HE_ROW_FLOOR 60.0

BF_FN void bf_he_row_floor(const double *p0, const double *lam, bf_he_pconst *pc)
{
    const double p[1][3] = { { p0[0], p0[1], p0[2] } };
    bf_geom n;
    n.ix = n.iy = n.ox = n.oy = BF_R(0.0);
    n.iz = n.oz = n.nh = n.vh = BF_R(1.0);
    BF_REAL K[3];
    bf_he_fd_lanes(&n, p, 0, lam, pc, 0, K, (BF_REAL(*)[3])0, (bf_he_memo *)0);
    for (int ch = 0; ch < 3; ch++) {
        const double kn = BF_LAST(K[ch]);
        pc->ldead[ch] = kn > 0.0 ? fmax(BF_HE_LN_DEAD, log(kn) - BF_HE_ROW_FLOOR) : BF_HE_LN_DEAD;
    }
}

/* 1 when no lane of g (BF_NLANES bins' geometry) needs its row made at p0:
 * each is either not read (live 0: no sample of its bin is flat) or dead in
 * every channel at every point for certain (0 in the rows, as
 * bf_he_fd_lanes would make it), from a bound that takes a few logarithms
 * instead of the series' search for its peak.  With F <= 1 and S = 1 (flat),
 * K's scale e^lk is at most kt^2 G / (pi cos ti cos to), and with P the
 * Poisson weights of g, V = sum_m P(m) e^(-a/m) / m is at most
 * e^(-a/M) + P(m >= M) <= e^(-a/M) + e^(M (1 + ln(g/M)) - g) for any M > g
 * (Chernoff).  With M = a / w, w = 2 + ln(kt^2 G / (pi ci co)) - ldead,
 * both are at most e^-w, so lpk + lk <= ln V + lk <= ln 2 - 2 + ldead < ldead:
 * bf_he_series_x leaves the lane dead.  Only where g < 18 / BF_HE_FD_MARGIN,
 * so that no rough limit enters the value or a neighbour. */
BF_FN int bf_he_rows_dead(const bf_geom *g, BF_REAL live, const double *p0, const double *lam,
                          const bf_he_pconst *pc)
{
    bf_he_dir d;
    bf_he_dir_make(g, &d);
    BF_REAL lscale = d.lg2 - log(BF_PI * (d.ci * d.co)); /* ln G / (pi ci co) */
    BF_REAL vxy2 = d.vxy2, lnv2 = d.lvxy2;
    BF_REAL s0v = p0[1] * d.vz, lns0v2 = 2.0 * log(s0v);
    BF_REAL dead = BF_SEL(BF_R(1.0), BF_R(0.0), live > 0.0);
    BF_REAL all = BF_R(1.0);
    for (int ch = 0; ch < 3; ch++) {
        const double kl = 2.0 * BF_PI / lam[ch], kt = BF_PI * p0[0] / (2.0 * lam[ch]);
        BF_REAL gg = (kl * kl) * (s0v * s0v), lng = pc->lkl2[ch] + lns0v2;
        BF_REAL aa = (4.0 * (kt * kt)) * vxy2, la = pc->l4kt2[ch] + lnv2;
        BF_REAL w = 2.0 + (lscale + pc->lkt2[ch]) - pc->ldead[ch];
        BF_REAL lw = log(fmax(w, BF_R(1.0)));
        BF_REAL M = aa / fmax(w, BF_R(1.0)), lnM = la - lw;
        BF_REAL tail = M * (1.0 + lng - lnM) - gg;
        all = BF_SEL(BF_R(0.0), all,
                     (w >= 1.0) && (gg < BF_HE_G_LO / BF_HE_FD_MARGIN) && (M > gg) && (tail <= -w));
    }
    dead = BF_SEL(dead, BF_R(1.0), all > 0.0);
    return !BF_ANY(dead <= 0.0);
}

/* A pass's rows (see above) of the bins h0 .. h1 of the bin table `bins`
 * (BF_B_* above) at p[0..np]: field f = 3 j + c (K cos ti cos to at p[j] in
 * channel c) of bin hd into rows[f * nrows + hd], BF_NLANES bins at a time
 * (so also bins up to h1 + BF_NLANES - 1), with the floor of
 * bf_he_row_floor.  A run of bins where no sample can be flat at p[0]
 * (BF_B_COT, with a margin for rounding) is skipped: no lane of theirs
 * reads its row. */
BF_FN void bf_he_bin_rows(BF_GLOBAL const double *bins, int h0, int h1, const double (*p)[3],
                          int np, const double *lam, BF_GLOBAL double *rows, int nrows)
{
    const double cot_flat = (2.0 * BF_HE_U_FLAT) * p[0][1] / p[0][0] * (1.0 - 1e-9);
    bf_he_pconst pc;
    bf_he_pconst_make(p[0][0], lam, &pc);
    bf_he_row_floor(p[0], lam, &pc);
    for (int h = h0; h <= h1; h += BF_NLANES) {
        BF_REAL cot = BF_LOADG(bins + BF_B_COT * BF_NHD_PAD + h);
        BF_REAL live = BF_SEL(BF_R(0.0), BF_R(1.0), cot >= cot_flat);
        if (!BF_ANY(live > 0.0))
            continue;
        bf_geom g;
        g.ix = BF_LOADG(bins + BF_B_IX * BF_NHD_PAD + h);
        g.iy = BF_LOADG(bins + BF_B_IY * BF_NHD_PAD + h);
        g.iz = BF_LOADG(bins + BF_B_IZ * BF_NHD_PAD + h);
        g.ox = BF_LOADG(bins + BF_B_OX * BF_NHD_PAD + h);
        g.oy = BF_LOADG(bins + BF_B_OY * BF_NHD_PAD + h);
        g.oz = BF_LOADG(bins + BF_B_OZ * BF_NHD_PAD + h);
        g.nh = BF_LOADG(bins + BF_B_NH * BF_NHD_PAD + h);
        g.vh = BF_LOADG(bins + BF_B_VH * BF_NHD_PAD + h);
        BF_REAL K0[3], Kj[BF_HE_NP][3];
        if (bf_he_rows_dead(&g, live, p[0], lam, &pc)) {
            for (int f = 0; f < 3 * (1 + np); f++)
                BF_STORE(BF_R(0.0), rows + f * nrows + h);
            continue;
        }
        bf_he_fd_lanes(&g, p, np, lam, &pc, 1, K0, Kj, (bf_he_memo *)0);
        BF_REAL cc = fmax(g.iz, BF_HE_COS_MIN) * fmax(g.oz, BF_HE_COS_MIN);
        for (int c = 0; c < 3; c++)
            BF_STORE(K0[c] * cc, rows + c * nrows + h);
        for (int j = 0; j < np; j++)
            for (int c = 0; c < 3; c++)
                BF_STORE(Kj[j][c] * cc, rows + (3 * (1 + j) + c) * nrows + h);
    }
}

/* K at p[0] and at the np <= 3 forward-difference neighbours p[1..np] (each
 * p[j] = (tau, sigma0, n), a small step from p[0]) for one data pass:
 * K0[c] = bf_he(p[0]) bit for bit without a memo (to ~1e-12 with one),
 * Kj[j-1][c] = bf_he(p[j]) to second order in the step.
 *
 * All the transcendental work is done once, at p[0]: the series (most of
 * it) with the partials of its log in g and a, the shadowing and sigma with
 * theirs in u.  A neighbour is then a few dozen flops: u' exactly, S, erfc
 * and x (hence sigma, g') to first order (bf_he_rough_step), F and a'
 * exactly, the scale e^(lk' - lk) = (fs' / fs)(kt' / kt)^2 exactly, and
 *     series  V' = e^(lk' - lk) V e^x,  x = dlnV/dg (g' - g) + dlnV/da (a' - a)
 *             (e^x by its cubic: |x| is ~1e-4 at most where it matters),
 *     limit   L' = L e^(lk' - lk) e^(a/g - a'/g') g / g'   (one exp, exact),
 * blended by the weight t(g') as bf_he_dblend blends the value; a step in
 * n alone scales K by F' / F.  The series is carried in its log because ln V is
 * close to linear in g and a where V itself is not (d lnV / d ln tau reaches
 * ~1e3 on smooth materials).  The remainder is O(h^2) in the relative step
 * h ~ 1e-7: of the order of the forward difference's own truncation error
 * (tests/test_he.c measures it: the difference quotients agree with those
 * of exact evaluations to 1.4e-5 of their size).  A lane whose series is
 * dead (0) at p[0] stays 0, and one with F S = 0 (n = 1) stays 0.  The
 * series is also summed for g in [19, 19 m) and the limit made for g in
 * (18 / m, 18], m = BF_HE_FD_MARGIN, where the value does not use them, so
 * that a step across 19 or 18 is covered; a step of 1e-3 relative in g
 * would not be.  np = 0 with no memo is bf_he.  The memos: see bf_he_memo
 * (the series) and bf_he_flat (the bin rows).
 *
 * In steps: with a memo that has rows, a vector whose lanes are all flat
 * takes them (bf_he_bin_serve when its lanes share a bin, else
 * bf_he_bin_gather); else bf_he_fd_lanes: bf_he_fd_base (the directions, S,
 * sigma, F), bf_he_fd_channel per channel (the value, through
 * bf_he_dblend), bf_he_fd_neighbour per neighbour.
 *
 * bf_he_fd_factored is bf_he_fd, and with q != NULL it returns a vector
 * whose lanes share a bin's row in factored form: 1, and *q (bf_he_bin_q),
 * K0 and Kj left unset, its K at p[j] in channel c being memo->bk[j][c] * q
 * (bk changes only with memo->bgen; bf_fold in bf_pass.h sums such vectors
 * per bin).  Otherwise (0) K0 and Kj are set as bf_he_fd sets them. */
BF_FN int bf_he_fd_factored(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                            BF_REAL *K0, BF_REAL (*Kj)[3], bf_he_memo *memo, BF_REAL *q)
{
    bf_he_pconst own, *pc = memo ? &memo->pc : &own;
    if (!memo || !bf_he_pconst_for(pc, p[0][0], lam))
        bf_he_pconst_make(p[0][0], lam, pc);
    if (memo && memo->rows) {
        bf_he_flat fl;
        if (bf_he_flat_sure(g, memo->bins, memo->vhd, memo->cot_sure, &fl))
            memo->bsure += 1.0;
        else
            bf_he_flat_make(g, p[0][0], p[0][1], &fl);
        if (!BF_ANY(fl.lanes <= 0.0)) {
            BF_REAL qv = bf_he_bin_q(&fl);
            const double hd = BF_LAST(memo->vhd);
            memo->bhits += 1.0;
            if (BF_ANY(memo->vhd != hd)) {
                bf_he_bin_gather(memo, qv, np, K0, Kj);
                return 0;
            }
            if (memo->bgen != 1.0 + hd)
                bf_he_bin_load(memo, (int)hd, np);
            if (q)
                *q = qv;
            else
                bf_he_bin_serve(memo, qv, np, K0, Kj);
            return 1;
        }
    }
    bf_he_fd_lanes(g, p, np, lam, pc, 0, K0, Kj, memo);
    return 0;
}

/* K0 and Kj always set (the factored vectors' too). */
BF_FN void bf_he_fd(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                    BF_REAL *K0, BF_REAL (*Kj)[3], bf_he_memo *memo)
{
    bf_he_fd_factored(g, p, np, lam, K0, Kj, memo, (BF_REAL *)0);
}

/* K per channel into K[0..2] at wavelengths lam[0..2]: bf_he_fd's value. */
BF_FN void bf_he(const bf_geom *g, double tau, double sigma0, double n, const double *lam,
                 BF_REAL *K)
{
    const double p[1][3] = { { tau, sigma0, n } };
    bf_he_fd(g, p, 0, lam, K, (BF_REAL(*)[3])0, (bf_he_memo *)0);
}

/* The He model's entry point (the shape of bf_models.h's bf_lobe_<model>);
 * its forward differences are bf_he_fd (bf_lobe_fd_he in bf_lobe.h hands it
 * the pass state). */
BF_FN void bf_lobe_he(const bf_geom *g, const double *p, const double *lam, BF_REAL *K)
{
    bf_he(g, p[0], p[1], p[2], lam, K);
}

#endif /* BF_HE_H */
