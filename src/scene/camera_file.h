// ParaView camera files (.pvcc: File > Save Camera, or "Adjust Camera" > Configurations > Save):
// the render view's camera as a PVCameraConfiguration XML document, read and written so that a
// view moves ParaView -> shellmarch -> ParaView unchanged.
//
//   <PVCameraConfiguration description="ParaView camera configuration" version="1.0">
//     <Proxy group="views" type="RenderView" id="..." servers="21">
//       <Property name="CameraPosition" id="....CameraPosition" number_of_elements="3">
//         <Element index="0" value="..."/> ...
//       </Property>
//       ... CameraFocalPoint, CameraViewUp, CenterOfRotation, RotationFactor, CameraViewAngle,
//       CameraParallelScale, CameraParallelProjection (0 or 1)
//     </Proxy>
//   </PVCameraConfiguration>
//
// CameraPosition, CameraFocalPoint, CameraViewUp and CameraViewAngle are required;
// CameraParallelProjection defaults to 0 and CameraParallelScale is required when it is 1 (ParaView
// writes all six). Other properties are ignored.
#pragma once

#include <string>
#include <string_view>

#include "scene/camera.h"

namespace sm::scene {

// Throws sm::FileError naming `name` (the file) and, where one is at fault, the property.
Camera parseCameraFile(std::string_view text, const std::string& name);
Camera readCameraFile(const std::string& path);

// The document ParaView writes for this camera (CenterOfRotation at the point looked at); every
// number is written with 17 significant digits, so reading it back gives the same camera.
std::string cameraFileText(const Camera& c);
void writeCameraFile(const std::string& path, const Camera& c);  // atomically

}  // namespace sm::scene
