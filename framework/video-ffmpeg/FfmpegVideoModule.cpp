// mvcl-video-ffmpeg.so: H.264 video through FFmpeg's libraries (libavformat, libavcodec,
// libswscale), loaded by FrameWriter.cpp the first time a video file is written. It links FFmpeg
// and nothing of mvcl; the interface is the C struct of VideoModuleAbi_p.h.

#include "VideoModuleAbi_p.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <string>

namespace {

thread_local std::string lastError;

const char *failure(const std::string &what, int code = 0) {
    lastError = what;
    if (code < 0) {
        char text[AV_ERROR_MAX_STRING_SIZE] = {};
        av_strerror(code, text, sizeof text);
        lastError.append(": ").append(text);
    }
    return lastError.c_str();
}

struct Video {
    AVFormatContext *format = nullptr;
    AVCodecContext *codec = nullptr;
    AVStream *stream = nullptr;
    AVFrame *frame = nullptr;
    AVPacket *packet = nullptr;
    SwsContext *scale = nullptr;
    int width = 0, height = 0; // of the RGB input
    int64_t nextPts = 0;
    bool headerWritten = false;

    ~Video() {
        sws_freeContext(scale);
        av_packet_free(&packet);
        av_frame_free(&frame);
        avcodec_free_context(&codec);
        if (format) {
            if (format->pb && !(format->oformat->flags & AVFMT_NOFILE)) avio_closep(&format->pb);
            avformat_free_context(format);
        }
    }

    /// Sends `input` (null: flush) and writes every packet the encoder gives back.
    const char *encode(const AVFrame *input) {
        int code = avcodec_send_frame(codec, input);
        if (code < 0) return failure("encoding failed", code);
        for (;;) {
            code = avcodec_receive_packet(codec, packet);
            if (code == AVERROR(EAGAIN) || code == AVERROR_EOF) return nullptr;
            if (code < 0) return failure("encoding failed", code);
            av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
            packet->stream_index = stream->index;
            code = av_interleaved_write_frame(format, packet);
            if (code < 0) return failure("writing the video failed", code);
        }
    }
};

void *openVideo(const char *path, int width, int height, int rateNumerator, int rateDenominator, const char **error) {
    // Our errors say what failed in one line; FFmpeg's and x264's own log lines would add noise.
    av_log_set_level(AV_LOG_QUIET);
    auto video = new Video;
    const auto fail = [&](const char *message) -> void * {
        *error = message;
        delete video;
        return nullptr;
    };
    video->width = width;
    video->height = height;
    int code = avformat_alloc_output_context2(&video->format, nullptr, nullptr, path);
    if (code < 0 || !video->format) return fail(failure("no video container for this extension", code));
    const AVCodec *encoder = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!encoder) return fail(failure("this FFmpeg has no H.264 encoder (libx264)"));
    video->stream = avformat_new_stream(video->format, nullptr);
    video->codec = avcodec_alloc_context3(encoder);
    video->frame = av_frame_alloc();
    video->packet = av_packet_alloc();
    if (!video->stream || !video->codec || !video->frame || !video->packet) return fail(failure("out of memory"));
    // yuv420p, which every player decodes, halves the chroma resolution: the sides must be even.
    video->codec->width = width & ~1;
    video->codec->height = height & ~1;
    if (video->codec->width == 0 || video->codec->height == 0) return fail(failure("a video needs at least 2 x 2 pixels"));
    video->codec->pix_fmt = AV_PIX_FMT_YUV420P;
    video->codec->time_base = AVRational{rateDenominator, rateNumerator};
    video->codec->framerate = AVRational{rateNumerator, rateDenominator};
    video->codec->gop_size = 12;
    if (video->format->oformat->flags & AVFMT_GLOBALHEADER) video->codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    // Quality over size: a clip of lens edges and fine outlines should not smear.
    av_opt_set(video->codec->priv_data, "crf", "18", 0);
    av_opt_set(video->codec->priv_data, "preset", "medium", 0);
    code = avcodec_open2(video->codec, encoder, nullptr);
    if (code < 0) return fail(failure("cannot open the H.264 encoder", code));
    code = avcodec_parameters_from_context(video->stream->codecpar, video->codec);
    if (code < 0) return fail(failure("cannot set up the video stream", code));
    video->stream->time_base = video->codec->time_base;
    video->stream->avg_frame_rate = video->codec->framerate;
    video->frame->format = video->codec->pix_fmt;
    video->frame->width = video->codec->width;
    video->frame->height = video->codec->height;
    code = av_frame_get_buffer(video->frame, 0);
    if (code < 0) return fail(failure("out of memory", code));
    video->scale = sws_getContext(width, height, AV_PIX_FMT_RGB24, video->codec->width, video->codec->height,
                                  AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (!video->scale) return fail(failure("cannot convert RGB to YUV"));
    if (!(video->format->oformat->flags & AVFMT_NOFILE)) {
        code = avio_open(&video->format->pb, path, AVIO_FLAG_WRITE);
        if (code < 0) return fail(failure("cannot create the file", code));
    }
    code = avformat_write_header(video->format, nullptr);
    if (code < 0) return fail(failure("cannot write the video header", code));
    video->headerWritten = true;
    return video;
}

const char *writeFrame(void *handle, const unsigned char *rgb) {
    auto *video = static_cast<Video *>(handle);
    int code = av_frame_make_writable(video->frame);
    if (code < 0) return failure("out of memory", code);
    const uint8_t *source[1] = {rgb};
    const int stride[1] = {video->width * 3};
    sws_scale(video->scale, source, stride, 0, video->height, video->frame->data, video->frame->linesize);
    video->frame->pts = video->nextPts++;
    return video->encode(video->frame);
}

const char *closeVideo(void *handle) {
    auto *video = static_cast<Video *>(handle);
    const char *error = nullptr;
    if (video->headerWritten) {
        error = video->encode(nullptr);
        const int code = av_write_trailer(video->format);
        if (!error && code < 0) error = failure("cannot finish the video file", code);
    }
    delete video;
    return error;
}

const MvclVideoModule kModule{MVCL_VIDEO_MODULE_ABI, sizeof(MvclVideoModule), openVideo, writeFrame, closeVideo};

} // namespace

extern "C" __attribute__((visibility("default"))) const MvclVideoModule *mvcl_video_module() { return &kModule; }
