// Lucerna (host): IES LM-63 photometric files (1986, 1991, 1995, 2002), photometric types C, B and A,
// TILT data: a strict reader (every malformed file is a SceneError at FILE:LINE) and the candela
// value of the web at any (vertical, horizontal) angle, bilinear in the two angles with the
// horizontal symmetry unfolded. Axis conventions: docs/lights.md, "IES LM-63 files".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "lucerna/scene/error.h"

namespace lu {

// How the horizontal angles of a web cover their range (LM-63-2002, 4.17): the full circle for
// type C, -90..90 for types A and B.
enum class IESSymmetry {
    Rotational,   // type C, one horizontal angle (0): the same in every plane
    Quadrant,     // type C, 0..90: symmetric about the 0-180 and the 90-270 planes
    Half0To180,   // type C, 0..180: symmetric about the 0-180 plane
    Half90To270,  // type C, 90..270: symmetric about the 90-270 plane
    Full,         // type C, 0..360
    Lateral,      // types A, B, 0..90: laterally symmetric, I(v, -h) = I(v, h)
    LateralFull   // types A, B, -90..90
};

struct IESProfile {
    std::string filename;
    std::string format;                  // "LM-63-2002", "LM-63-1995", "LM-63-1991" or "LM-63-1986"
    std::string tilt;                    // "NONE", "INCLUDE" or the file name of TILT=<file>
    std::string tiltFile;                // TILT=<file>: the path read (relative to the IES file's folder)
    int tiltGeometry = 0;                // lamp-to-luminaire geometry 1, 2 or 3; 0: TILT=NONE
    std::vector<double> tiltAngles;      // degrees, strictly increasing, in [0, 90]
    std::vector<double> tiltFactors;     // the multiplying factor at each tilt angle
    double tiltAngle = 0;                // the tilt applied (SetTilt); tiltFactor is its factor
    double tiltFactor = 1;               // 1: not tilted (the photometry as measured)
    bool tiltApplied = false;
    int photometricType = 1;             // 1: type C, 2: type B, 3: type A
    int lamps = 1;
    double lumensPerLamp = -1;           // -1: absolute photometry
    double candelaMultiplier = 1, ballastFactor = 1, ballastLampFactor = 1, inputWatts = 0;
    std::vector<double> vertical;        // degrees, strictly increasing, in [0, 180] (C) or [-90, 90] (A, B)
    std::vector<double> horizontal;      // degrees, strictly increasing
    std::vector<double> candela;         // as in the file: candela[h * vertical.size() + v]
    IESSymmetry symmetry = IESSymmetry::Rotational;

    // The factor every candela value is multiplied by: candela multiplier * ballast factor *
    // ballast-lamp photometric factor (LM-63-1995; "future use", normally 1, in LM-63-2002) * the
    // tilt factor (1 unless SetTilt applied one).
    double Factor() const { return candelaMultiplier * ballastFactor * ballastLampFactor * tiltFactor; }
    char TypeLetter() const { return photometricType == 1 ? 'C' : photometricType == 2 ? 'B' : 'A'; }
    // The tilt table's factor at `degrees` (linear between the tilt angles); false where there is no
    // table (TILT=NONE) or `degrees` is outside [first, last] tilt angle (LM-63 gives no data there).
    bool TiltFactorAt(double degrees, double *factor) const;
    // Applies the tilt: every candela value is multiplied by TiltFactorAt(degrees) (which must hold).
    void SetTilt(double degrees);
    // Luminous intensity (cd, Factor() applied) at vertical angle v and horizontal angle h, degrees.
    // Type C: v from nadir (0) to zenith (180), h any value, unfolded by the symmetry. Types A, B:
    // v and h in [-90, 90] (h mirrored for a laterally symmetric web). 0 outside the web's ranges.
    double Evaluate(double v, double h) const;
    double MaxCandela() const;           // largest value of the web, Factor() applied
    // "LM-63-2002, type C, TILT=NONE, 37 vertical x 1 horizontal angles (rotationally symmetric), ..."
    std::string Describe() const;
};

// Parses the text of an IES file named `filename`; a malformed file throws SceneError at
// filename:line with a message naming what is wrong, followed by `context` (e.g. "in the IES file of
// LightSource \"goniometric\" at scene.pbrt:4:1"). TILT=<file> reads that file, relative to
// filename's folder (its errors: at its own FILE:LINE).
IESProfile ParseIES(std::string_view text, const std::string &filename, const std::string &context);
// Reads and parses `path` (a missing or unreadable file: SceneError at `referencedFrom`).
IESProfile ReadIES(const std::string &path, const FileLoc &referencedFrom, const std::string &context);

// The profile as a vertex table for the goniometric light: (n+1) x (n+1) candela values (rows
// top first) at the directions of the equal-area points (i, j) / n in the goniometric light's
// image frame (lights.h, ProfileValueAt; n even). The axis convention (docs/lights.md): type C's
// nadir (vertical 0) is the frame's -z, horizontal 0 its +x and horizontal 90 its -y, so that after
// pbrt-v4's y/z swap the luminaire hangs along the light's -y with C0 along +x and C90 along -z
// (counterclockwise seen from above, +y). Types A and B: the photometric axis (0, 0) is the frame's
// -z too, vertical +90 its +x and horizontal +90 its +y (light: +x and +z); type B's polar axis is
// the frame's y (the luminaire's lateral axis), type A's its x (the luminaire's vertical axis).
std::vector<float> IESEqualAreaTable(const IESProfile &profile, int n);
// The (vertical, horizontal) angles, degrees, of a unit direction w of that frame for photometric
// type `type` (1: C, horizontal in [0, 360); 2: B, 3: A, both angles in (-180, 180]).
void IESAnglesOfDirection(float wx, float wy, float wz, double *vertical, double *horizontal, int type = 1);

}  // namespace lu
