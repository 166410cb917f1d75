// Lucerna benchmark (issue 14): memory of N instances of a 12-triangle cube in Embree 3, native
// RTC_GEOMETRY_TYPE_INSTANCE per instance (mode 0) against one user geometry whose primitives are
// the instances (mode 1; optional build quality 0 low / 1 medium / 2 high, and a 4th argument: compact).
// Standalone, not built by CMake: g++ -O2 -o /tmp/eim bench/embree_instance_memory.cpp -lembree3
// then /tmp/eim N MODE [QUALITY [compact]]; docs/benchmarks.md ("Object instancing") has the numbers.
#include <embree3/rtcore.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>
#include <sys/resource.h>
static long rss(){ struct rusage u; getrusage(RUSAGE_SELF,&u); return u.ru_maxrss; }
struct Ctx { RTCScene proto; unsigned n; };
int main(int argc,char**argv){
  unsigned N=atoi(argv[1]); int mode=atoi(argv[2]);
  RTCDevice dev=rtcNewDevice(nullptr);
  RTCScene proto=rtcNewScene(dev);
  RTCGeometry g=rtcNewGeometry(dev,RTC_GEOMETRY_TYPE_TRIANGLE);
  float*vb=(float*)rtcSetNewGeometryBuffer(g,RTC_BUFFER_TYPE_VERTEX,0,RTC_FORMAT_FLOAT3,12,8);
  for(int i=0;i<8;i++){vb[3*i]=i&1;vb[3*i+1]=(i>>1)&1;vb[3*i+2]=(i>>2)&1;}
  unsigned*ib=(unsigned*)rtcSetNewGeometryBuffer(g,RTC_BUFFER_TYPE_INDEX,0,RTC_FORMAT_UINT3,12,12);
  for(int i=0;i<36;i++) ib[i]=(i*5)%8;
  rtcCommitGeometry(g); rtcAttachGeometry(proto,g); rtcReleaseGeometry(g); rtcCommitScene(proto);
  long r0=rss();
  RTCScene top=rtcNewScene(dev); if(argc>3) rtcSetSceneBuildQuality(top,RTCBuildQuality(atoi(argv[3]))); if(argc>4) rtcSetSceneFlags(top,RTC_SCENE_FLAG_COMPACT);
  if(mode==0){
    for(unsigned i=0;i<N;i++){
      RTCGeometry in=rtcNewGeometry(dev,RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(in,proto);
      float x[12]={1,0,0,0,1,0,0,0,1,float(i%1000)*2,float((i/1000)%1000)*2,float(i/1000000)*2};
      rtcSetGeometryTransform(in,0,RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR,x);
      rtcCommitGeometry(in); rtcAttachGeometry(top,in); rtcReleaseGeometry(in);
    }
  } else {
    RTCGeometry u=rtcNewGeometry(dev,RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(u,N);
    rtcSetGeometryBoundsFunction(u,[](const RTCBoundsFunctionArguments*a){unsigned i=a->primID;
      float x=float(i%1000)*2,y=float((i/1000)%1000)*2,z=float(i/1000000)*2;
      a->bounds_o->lower_x=x;a->bounds_o->lower_y=y;a->bounds_o->lower_z=z;
      a->bounds_o->upper_x=x+1;a->bounds_o->upper_y=y+1;a->bounds_o->upper_z=z+1;},nullptr);
    rtcSetGeometryIntersectFunction(u,[](const RTCIntersectFunctionNArguments*){});
    rtcCommitGeometry(u); rtcAttachGeometry(top,u); rtcReleaseGeometry(u);
  }
  long r1=rss();
  rtcCommitScene(top);
  long r2=rss();
  printf("mode %d N %u: rss before %ld KB, after create %ld KB, after commit %ld KB; per instance %.1f B\n",mode,N,r0,r1,r2,(r2-r0)*1024.0/N);
}
