// Lucerna (host): IES LM-63 photometric files (1986, 1991, 1995, 2002), type C photometry: a strict
// reader (every malformed file is a SceneError at FILE:LINE) and the candela value of the web at
// any (vertical, horizontal) angle, bilinear in the two angles with the horizontal symmetry unfolded.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "lucerna/scene/error.h"

namespace lu {

// How the horizontal angles of a type C web cover the full circle (LM-63-2002, 4.17).
enum class IESSymmetry {
    Rotational,   // one horizontal angle (0): the same in every plane
    Quadrant,     // 0..90: symmetric about the 0-180 and the 90-270 planes
    Half0To180,   // 0..180: symmetric about the 0-180 plane
    Half90To270,  // 90..270: symmetric about the 90-270 plane
    Full          // 0..360
};

struct IESProfile {
    std::string filename;
    std::string format;                  // "LM-63-2002", "LM-63-1995", "LM-63-1991" or "LM-63-1986"
    std::string tilt;                    // "NONE" or "INCLUDE"
    int photometricType = 1;             // 1: type C (the only one read)
    int lamps = 1;
    double lumensPerLamp = -1;           // -1: absolute photometry
    double candelaMultiplier = 1, ballastFactor = 1, ballastLampFactor = 1, inputWatts = 0;
    std::vector<double> vertical;        // degrees, strictly increasing, in [0, 180]
    std::vector<double> horizontal;      // degrees, strictly increasing
    std::vector<double> candela;         // as in the file: candela[h * vertical.size() + v]
    IESSymmetry symmetry = IESSymmetry::Rotational;

    // The factor every candela value is multiplied by: candela multiplier * ballast factor *
    // ballast-lamp photometric factor (LM-63-1995; "future use", normally 1, in LM-63-2002).
    double Factor() const { return candelaMultiplier * ballastFactor * ballastLampFactor; }
    // Luminous intensity (cd, Factor() applied) at vertical angle v (0: nadir, 180: zenith) and
    // horizontal angle h (any value; unfolded by the symmetry), degrees. 0 outside the vertical range.
    double Evaluate(double v, double h) const;
    double MaxCandela() const;           // largest value of the web, Factor() applied
    // "LM-63-2002, type C, 37 vertical x 1 horizontal angles (rotationally symmetric), peak 1000 cd"
    std::string Describe() const;
};

// Parses the text of an IES file named `filename`; a malformed file throws SceneError at
// filename:line with a message naming what is wrong, followed by `context` (e.g. "in the IES file of
// LightSource \"goniometric\" at scene.pbrt:4:1").
IESProfile ParseIES(std::string_view text, const std::string &filename, const std::string &context);
// Reads and parses `path` (a missing or unreadable file: SceneError at `referencedFrom`).
IESProfile ReadIES(const std::string &path, const FileLoc &referencedFrom, const std::string &context);

// The profile as a vertex table for the goniometric light: (n+1) x (n+1) candela values (rows
// top first) at the directions of the equal-area points (i, j) / n in the goniometric light's
// image frame (lights.h, ProfileValueAt; n even). The axis convention (docs/lights.md): nadir (vertical 0) is the frame's -z, horizontal
// 0 its +x and horizontal 90 its -y, so that after pbrt-v4's y/z swap the luminaire hangs along
// the light's -y with C0 along +x and C90 along -z (counterclockwise seen from above, +y).
std::vector<float> IESEqualAreaTable(const IESProfile &profile, int n);
// The (vertical, horizontal) angles, degrees, of a unit direction w of that frame.
void IESAnglesOfDirection(float wx, float wy, float wz, double *vertical, double *horizontal);

}  // namespace lu
